// cga-cuda-bench: crowd skinning throughput on one CUDA device, per method and vertex layout, against the
// device's measured copy bandwidth. Each instance has its own copy of the rest mesh (a crowd streams
// distinct vertices), 64 bones by default, >= 10^7 vertices in all. Two meshes: `coherent`
// (make_coherent_skinned_mesh: neighbouring vertices share bones as in the real characters, the main row)
// and `random` (4 random bones per vertex: the worst case for the shared-memory palette reads); the header
// prints each mesh's joints per 32-vertex warp and the modelled shared-memory wavefronts per palette read. For every row it
// prints vertices/s, bytes moved per vertex, the bandwidth bound (copy bandwidth / bytes per vertex) and
// the fraction of it reached, and checks two instances against the CPU SkinningJob (exit status 1 when a
// result is off by more than 1e-4 of the scene size).
//
//   cga-cuda-bench [--vertices N] [--instances I] [--bones B] [--iterations K] [--normals] [--layout standard|compact|both]
//                  [--mesh coherent|random|both]
#include <cuda_runtime_api.h>

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cga/cuda/crowd_skinning.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/crowd_meshes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

using namespace cga;
using namespace cga::cuda;

namespace {

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw CudaError(std::string(what) + ": " + cudaGetErrorString(e));
}

// An owning device allocation.
struct DeviceBuffer {
  void* ptr = nullptr;
  std::size_t bytes = 0;
  explicit DeviceBuffer(std::size_t n) : bytes(n) {
    check(cudaMalloc(&ptr, n), ("cudaMalloc of " + std::to_string(n) + " bytes").c_str());
  }
  ~DeviceBuffer() { cudaFree(ptr); }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  template <class T>
  T* as() const { return static_cast<T*>(ptr); }
};

// Uploads one instance's data and replicates it `instances` times on the device (doubling copies).
void upload_replicated(DeviceBuffer& dst, const void* src, std::size_t one, std::size_t instances) {
  check(cudaMemcpy(dst.ptr, src, one, cudaMemcpyHostToDevice), "upload");
  for (std::size_t have = 1; have < instances;) {
    const std::size_t n = std::min(have, instances - have);
    check(cudaMemcpy(static_cast<char*>(dst.ptr) + have * one, dst.ptr, n * one, cudaMemcpyDeviceToDevice),
          "replicate");
    have += n;
  }
}

struct Options {
  std::size_t vertices = 16384;
  std::size_t instances = 4096;
  std::size_t bones = 64;
  int iterations = 20;
  bool normals = false;
  std::string layout = "both";
  std::string mesh = "both";
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + std::string(a));
      return argv[++i];
    };
    if (a == "--vertices") o.vertices = std::stoull(value());
    else if (a == "--instances") o.instances = std::stoull(value());
    else if (a == "--bones") o.bones = std::stoull(value());
    else if (a == "--iterations") o.iterations = std::stoi(value());
    else if (a == "--normals") o.normals = true;
    else if (a == "--layout") o.layout = value();
    else if (a == "--mesh") o.mesh = value();
    else if (a == "--help" || a == "-h") {
      fmt::print("usage: cga-cuda-bench [--vertices N] [--instances I] [--bones B] [--iterations K] [--normals] "
                 "[--layout standard|compact|both] [--mesh coherent|random|both]\n");
      std::exit(0);
    } else {
      throw std::invalid_argument("unknown option " + std::string(a) + " (see --help)");
    }
  }
  if (o.layout != "standard" && o.layout != "compact" && o.layout != "both")
    throw std::invalid_argument("--layout must be standard, compact or both");
  if (o.mesh != "coherent" && o.mesh != "random" && o.mesh != "both")
    throw std::invalid_argument("--mesh must be coherent, random or both");
  if (o.bones == 0 || o.bones > kMaxBones || (o.bones > 256)) throw std::invalid_argument("--bones must be 1..256");
  if (o.iterations < 1) throw std::invalid_argument("--iterations must be >= 1");
  return o;
}

// Device-to-device copy bandwidth (bytes read + written per second) of a 1 GiB copy.
double copy_bandwidth() {
  const std::size_t bytes = std::size_t{1} << 30;
  DeviceBuffer a(bytes), b(bytes);
  check(cudaMemset(a.ptr, 1, bytes), "memset");
  cudaEvent_t start, stop;
  check(cudaEventCreate(&start), "event"), check(cudaEventCreate(&stop), "event");
  check(cudaMemcpy(b.ptr, a.ptr, bytes, cudaMemcpyDeviceToDevice), "warm-up copy");
  constexpr int kRepeats = 10;
  check(cudaEventRecord(start), "record");
  for (int r = 0; r < kRepeats; ++r) check(cudaMemcpy(b.ptr, a.ptr, bytes, cudaMemcpyDeviceToDevice), "copy");
  check(cudaEventRecord(stop), "record");
  check(cudaEventSynchronize(stop), "sync");
  float ms = 0.0f;
  check(cudaEventElapsedTime(&ms, start, stop), "elapsed");
  cudaEventDestroy(start), cudaEventDestroy(stop);
  return 2.0 * static_cast<double>(bytes) * kRepeats / (ms * 1e-3);
}

}  // namespace

int main(int argc, char** argv) try {
  const Options opt = parse(argc, argv);
  int device = 0;
  check(cudaGetDevice(&device), "cudaGetDevice (is there a CUDA device?)");
  cudaDeviceProp prop{};
  check(cudaGetDeviceProperties(&prop, device), "cudaGetDeviceProperties");
  const std::size_t total = opt.vertices * opt.instances;
  fmt::print("device: {} (sm_{}{}), {} vertices per instance x {} instances = {} vertices, {} bones, {} iterations{}\n",
             prop.name, prop.major, prop.minor, opt.vertices, opt.instances, total, opt.bones, opt.iterations,
             opt.normals ? ", with normals" : "");
  const double bandwidth = copy_bandwidth();
  fmt::print("measured device-to-device copy: {:.3f} TB/s (read + write)\n\n", bandwidth * 1e-12);

  // 16 distinct rigid palettes, cycled over the instances; per mesh one rest mesh, replicated per instance.
  constexpr std::size_t kPalettes = 16;
  const RandomPalettes crowd = make_random_palettes(static_cast<int>(opt.bones), kPalettes, 500u);
  const auto& mats = crowd.matrices;
  const auto& dqs = crowd.dual_quats;
  const auto& mots = crowd.motors;
  const float scene_size = 6.0f;  // positions in [-1, 1]^3 moved by translations in [-1, 1]^3: within a 6-wide box

  std::vector<std::pair<const char*, SkinnedMesh>> meshes;  // coherent (the main rows), then random (stress)
  const int bones = static_cast<int>(opt.bones);
  if (opt.mesh != "random") meshes.emplace_back("coherent", make_coherent_skinned_mesh(opt.vertices, bones, 1234u, 1.0f));
  if (opt.mesh != "coherent") meshes.emplace_back("random", make_random_skinned_mesh(opt.vertices, bones, 1234u, 1.0f));
  for (const auto& [name, mesh] : meshes) {
    fmt::print("{} mesh: {}; modelled shared-memory wavefronts per palette read (4 = the minimum): ", name,
               describe(joint_coherence(mesh)));
    for (SkinningMethod m : kAllSkinningMethods)
      fmt::print("{} {:.2f}{}", to_string(m), modelled_palette_wavefronts(palette_layout(m, opt.bones), m, mesh.joints),
                 m == kAllSkinningMethods.back() ? "\n" : ", ");
  }
  fmt::print("palette in shared memory: {} copies over the bank groups ({} B per block, lbs)\n\n",
             palette_layout(SkinningMethod::lbs, opt.bones).copies,
             palette_layout(SkinningMethod::lbs, opt.bones).shared_bytes);

  bool all_ok = true;
  fmt::print("| mesh | method | layout | B/vertex | ms | G vertices/s | bound G vertices/s | fraction | max error |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& [mesh_name, mesh] : meshes) {
    std::vector<float> positions(3 * opt.vertices), normals(3 * opt.vertices);
    std::vector<std::array<std::uint8_t, 4>> joints8(opt.vertices);
    std::vector<std::array<std::uint16_t, 4>> weights16(opt.vertices);
    SkinnedMesh compact = mesh;  // the CPU reference of the compact layout: dequantized weights
    for (std::size_t v = 0; v < opt.vertices; ++v) {
      positions[3 * v] = mesh.px[v], positions[3 * v + 1] = mesh.py[v], positions[3 * v + 2] = mesh.pz[v];
      normals[3 * v] = mesh.nx[v], normals[3 * v + 1] = mesh.ny[v], normals[3 * v + 2] = mesh.nz[v];
      for (int k = 0; k < 4; ++k) {
        joints8[v][k] = static_cast<std::uint8_t>(mesh.joints[v][k]);
        weights16[v][k] = static_cast<std::uint16_t>(std::lround(mesh.weights[v][k] * 65535.0f));
        compact.weights[v][k] = weights16[v][k] / 65535.0f;
      }
    }
    DeviceBuffer d_pos(positions.size() * 4 * opt.instances);
    upload_replicated(d_pos, positions.data(), positions.size() * 4, opt.instances);
    std::unique_ptr<DeviceBuffer> d_nrm, d_out_nrm;
    if (opt.normals) {
      d_nrm = std::make_unique<DeviceBuffer>(normals.size() * 4 * opt.instances);
      upload_replicated(*d_nrm, normals.data(), normals.size() * 4, opt.instances);
      d_out_nrm = std::make_unique<DeviceBuffer>(3 * 4 * total);
    }
    DeviceBuffer d_out(3 * 4 * total);

    for (const bool use_compact : {false, true}) {
      if ((use_compact && opt.layout == "standard") || (!use_compact && opt.layout == "compact")) continue;
      const std::size_t jbytes = use_compact ? 4 : 8, wbytes = use_compact ? 8 : 16;
      DeviceBuffer d_joints(jbytes * total), d_weights(wbytes * total);
      if (use_compact) {
        upload_replicated(d_joints, joints8.data(), jbytes * opt.vertices, opt.instances);
        upload_replicated(d_weights, weights16.data(), wbytes * opt.vertices, opt.instances);
      } else {
        upload_replicated(d_joints, mesh.joints.data(), jbytes * opt.vertices, opt.instances);
        upload_replicated(d_weights, mesh.weights.data(), wbytes * opt.vertices, opt.instances);
      }
      const SkinnedMesh& reference_mesh = use_compact ? compact : mesh;
      for (SkinningMethod method : kAllSkinningMethods) {
        // Palettes of all instances (cycled), prepared: the entries the kernels' blends read.
        const std::vector<float> palettes = cycled_packed_palettes(method, mats, dqs, mots, opt.instances);
        DeviceBuffer d_pal(palettes.size() * 4);
        check(cudaMemcpy(d_pal.ptr, palettes.data(), d_pal.bytes, cudaMemcpyHostToDevice), "palette upload");

        CrowdArgs args;
        args.method = method;
        args.vertex_count = opt.vertices, args.instances = opt.instances, args.bones = opt.bones;
        args.per_instance_inputs = true;
        args.positions = d_pos.as<float>();
        args.normals = d_nrm ? d_nrm->as<float>() : nullptr;
        args.joints = d_joints.ptr, args.joint_format = use_compact ? JointFormat::u8x4 : JointFormat::u16x4;
        args.weights = d_weights.ptr, args.weight_format = use_compact ? WeightFormat::unorm16x4 : WeightFormat::f32x4;
        args.palettes = d_pal.as<float>();
        args.out_positions = d_out.as<float>();
        args.out_normals = d_out_nrm ? d_out_nrm->as<float>() : nullptr;

        launch_crowd_skinning(args);  // warm-up
        check(cudaDeviceSynchronize(), "warm-up");
        cudaEvent_t start, stop;
        check(cudaEventCreate(&start), "event"), check(cudaEventCreate(&stop), "event");
        check(cudaEventRecord(start), "record");
        for (int it = 0; it < opt.iterations; ++it) launch_crowd_skinning(args);
        check(cudaEventRecord(stop), "record");
        check(cudaEventSynchronize(stop), "sync");
        float ms = 0.0f;
        check(cudaEventElapsedTime(&ms, start, stop), "elapsed");
        cudaEventDestroy(start), cudaEventDestroy(stop);
        const double seconds = ms * 1e-3 / opt.iterations;
        const double rate = static_cast<double>(total) / seconds;
        const std::size_t bpv = bytes_per_vertex(args);
        const double bound = bandwidth / static_cast<double>(bpv);

        // Check the first and the last instance against the CPU job.
        float worst = 0.0f;
        for (const std::size_t inst : {std::size_t{0}, opt.instances - 1}) {
          const std::size_t p = inst % kPalettes;
          SkinnedOutput cpu;
          SkinningJob job = make_skinning_job(method, reference_mesh, cpu);
          job.matrices = mats[p], job.dual_quats = dqs[p], job.motors = mots[p];
          if (!job.Run()) throw std::runtime_error("the CPU reference job refused its input: " + job.ValidationError());
          std::vector<float> gpu(3 * opt.vertices);
          check(cudaMemcpy(gpu.data(), d_out.as<float>() + 3 * inst * opt.vertices, gpu.size() * 4,
                           cudaMemcpyDeviceToHost), "readback");
          for (std::size_t v = 0; v < opt.vertices; ++v) {
            const float d = std::hypot(gpu[3 * v] - cpu.px[v], gpu[3 * v + 1] - cpu.py[v], gpu[3 * v + 2] - cpu.pz[v]);
            worst = std::isfinite(d) ? std::max(worst, d) : INFINITY;
          }
        }
        const bool ok = worst <= 1e-4f * scene_size;
        all_ok = all_ok && ok;
        fmt::print("| {} | {} | {} | {} | {:.3f} | {:.2f} | {:.2f} | {:.0f} % | {:.2e}{} |\n", mesh_name, to_string(method),
                   use_compact ? "compact (u8 joints, unorm16 weights)" : "standard (u16 joints, f32 weights)", bpv,
                   ms / opt.iterations, rate * 1e-9, bound * 1e-9, 100.0 * rate / bound, worst, ok ? "" : " FAIL");
      }
    }
  }
  if (!all_ok) {
    fmt::print(stderr, "cga-cuda-bench: some results differ from the CPU SkinningJob by more than 1e-4 of the scene size\n");
    return 1;
  }
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "cga-cuda-bench: {}\n", e.what());
  return 2;
}
