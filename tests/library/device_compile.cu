// The generated CUDA libraries compiled for the device by nvcc (ctest library/cuda-device-compile, where nvcc
// is found): a kernel that calls functions of each, so that their __host__ __device__ wrappers and kernels are
// instantiated for the device. tests/library runs the same files as host C++ against the oracle.
#include "cga3.cuh"
#include "cga_rigid.cuh"
#include "e3.cuh"
#include "pga3.cuh"

__global__ void use_libraries(const pga3::motor* m, const pga3::point* p, pga3::point* q, const e3::bivector* b,
                              e3::rotor* r, const cga3::scaled_motor* s, const cga3::point* x, cga3::point* y,
                              const cga_rigid::motor* g, cga_rigid::motor* h, float* n, int count) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= count) return;
  q[i] = pga3::matrix(m[i], pga3::of<pga3::point_t>)(pga3::sandwich(m[i], p[i]));
  r[i] = e3::exp(0.5f * b[i]) * ~e3::normalize(e3::exp(b[i]));
  y[i] = cga3::sandwich(s[i], x[i]);
  h[i] = cga_rigid::exp(0.5f * cga_rigid::log(g[i]));
  n[i] = pga3::norm(pga3::log(m[i])) + (pga3::log(m[i]) & pga3::line{{0, 0, 0, 1, 0, 0}});
}
