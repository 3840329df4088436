// opencl_host CLFILE [NAME NIN NOUT IN OUT32 OUT64]...: builds CLFILE (the cgagen OpenCL files of several
// kernels plus the wrapper kernels run_NAME_f32 / run_NAME_f64 that targets_check appends) once, with
// -Werror, on the first OpenCL device (PoCL on the CPU in CI); per NAME runs one work item per input row in
// float and in double and writes the outputs one row per line. Exit 1 on any OpenCL error (with the build
// log).
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#define CHECK(x)                                                          \
  do {                                                                    \
    cl_int e_ = (x);                                                      \
    if (e_ != CL_SUCCESS) {                                               \
      std::fprintf(stderr, "opencl_host: %s failed: %d\n", #x, (int)e_); \
      std::exit(1);                                                       \
    }                                                                     \
  } while (0)

template <class T>
std::vector<T> run(cl_context ctx, cl_command_queue q, cl_program prog, const char* name, const std::vector<double>& in,
                   size_t rows, size_t nout) {
  cl_int err;
  std::vector<T> a(in.begin(), in.end()), out(rows * nout);
  cl_mem bin = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, a.size() * sizeof(T), a.data(), &err);
  CHECK(err);
  cl_mem bout = clCreateBuffer(ctx, CL_MEM_WRITE_ONLY, out.size() * sizeof(T), nullptr, &err);
  CHECK(err);
  cl_kernel k = clCreateKernel(prog, name, &err);
  CHECK(err);
  CHECK(clSetKernelArg(k, 0, sizeof bin, &bin));
  CHECK(clSetKernelArg(k, 1, sizeof bout, &bout));
  CHECK(clEnqueueNDRangeKernel(q, k, 1, nullptr, &rows, nullptr, 0, nullptr, nullptr));
  CHECK(clEnqueueReadBuffer(q, bout, CL_TRUE, 0, out.size() * sizeof(T), out.data(), 0, nullptr, nullptr));
  clReleaseKernel(k);
  clReleaseMemObject(bin);
  clReleaseMemObject(bout);
  return out;
}

template <class T>
void write(const std::string& path, const std::vector<T>& v, size_t nout) {
  std::ofstream out(path);
  char buf[64];
  for (size_t i = 0; i < v.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.17g", static_cast<double>(v[i]));
    out << buf << ((i + 1) % nout ? " " : "\n");
  }
}

int main(int argc, char** argv) {
  if (argc < 2 || (argc - 2) % 6 != 0) {
    std::fprintf(stderr, "usage: opencl_host CLFILE [NAME NIN NOUT IN OUT32 OUT64]...\n");
    return 2;
  }
  std::ifstream f(argv[1]);
  std::stringstream ss;
  ss << f.rdbuf();
  std::string src = ss.str();

  cl_platform_id platform;
  cl_uint n;
  CHECK(clGetPlatformIDs(1, &platform, &n));
  cl_device_id dev;
  CHECK(clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 1, &dev, &n));
  char dname[256] = {0}, ver[256] = {0};
  clGetDeviceInfo(dev, CL_DEVICE_NAME, sizeof dname, dname, nullptr);
  clGetDeviceInfo(dev, CL_DEVICE_VERSION, sizeof ver, ver, nullptr);
  cl_int err;
  cl_context ctx = clCreateContext(nullptr, 1, &dev, nullptr, nullptr, &err);
  CHECK(err);
  cl_command_queue q = clCreateCommandQueue(ctx, dev, 0, &err);
  CHECK(err);
  const char* s = src.c_str();
  cl_program prog = clCreateProgramWithSource(ctx, 1, &s, nullptr, &err);
  CHECK(err);
  cl_int b = clBuildProgram(prog, 1, &dev, "-cl-std=CL1.2 -Werror", nullptr, nullptr);
  size_t log_size = 0;
  clGetProgramBuildInfo(prog, dev, CL_PROGRAM_BUILD_LOG, 0, nullptr, &log_size);
  std::string log(log_size, '\0');
  clGetProgramBuildInfo(prog, dev, CL_PROGRAM_BUILD_LOG, log_size, log.data(), nullptr);
  if (b != CL_SUCCESS) {
    std::fprintf(stderr, "opencl_host: build failed (%d) on %s:\n%s\n", (int)b, dname, log.c_str());
    return 1;
  }
  std::printf("%s (%s)\n", dname, ver);
  for (int a = 2; a < argc; a += 6) {
    std::string name = argv[a];
    size_t nin = std::strtoul(argv[a + 1], nullptr, 10), nout = std::strtoul(argv[a + 2], nullptr, 10);
    std::vector<double> in;
    std::ifstream fin(argv[a + 3]);
    double v;
    while (fin >> v) in.push_back(v);
    size_t rows = in.size() / nin;
    write(argv[a + 4], run<float>(ctx, q, prog, ("run_" + name + "_f32").c_str(), in, rows, nout), nout);
    write(argv[a + 5], run<double>(ctx, q, prog, ("run_" + name + "_f64").c_str(), in, rows, nout), nout);
  }
  clReleaseProgram(prog);
  clReleaseCommandQueue(q);
  clReleaseContext(ctx);
  return 0;
}
