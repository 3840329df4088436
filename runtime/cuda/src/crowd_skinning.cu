// Crowd-skinning kernels: one thread per vertex (grid-stride), blockIdx.y = instance. Each block stages its
// instance's palette in shared memory, in copies spread over the bank groups (palette_slot in kernels.hpp:
// lane l reads copy l % copies, so a warp's 128-bit palette reads take the minimum 4 wavefronts whatever
// joints its vertices use); the per-vertex blend reads each entry into registers (load_entry) and blends
// those; cga_points converts every motor there once (a per-bone prepass)
// into its weight-normalized point-transform matrix with the generated transform_point_split_prepare (the
// prepare of the staged point transform; the point transform of a motor is affine, so the per-bone transform_point + divide + average the paper does per vertex equals blending
// these matrices), and cga_motors stages its motors in split form (G = a + b, H = a - b, U; see
// runtime/scripts/transform_point_split.clu: no cancellation for scaled motors), blends those 12 coefficients
// per vertex (sign fix on G) and moves the point by that prepare's matrix. Methods and input formats
// are template parameters.
#include <cuda_runtime.h>

#include <cstdint>

#include "cga/runtime/rotor_sign.hpp"
#include "kernels.hpp"
#include "transform_point_split.cuh"

namespace cga::cuda::detail {
namespace {

enum Method : int { kLbs = 0, kDqs = 1, kPoints = 2, kMotors = 3 };

constexpr int kBlock = 256;
constexpr int kVerticesPerThread = 4;  // grid-stride steps per thread, to amortize the palette staging

struct KernelArgs {
  unsigned vertex_count, bones, instance_offset, copy_shift;
  bool per_instance_inputs;
  const float* __restrict__ positions;
  const float* __restrict__ normals;
  const void* __restrict__ joints;
  const void* __restrict__ weights;
  const float* __restrict__ palettes;
  float* __restrict__ out_positions;
  float* __restrict__ out_normals;
};

template <bool kU8>
__device__ __forceinline__ void load_joints(const void* p, std::size_t i, int j[4]) {
  if constexpr (kU8) {
    const uchar4 v = __ldg(static_cast<const uchar4*>(p) + i);
    j[0] = v.x, j[1] = v.y, j[2] = v.z, j[3] = v.w;
  } else {
    const ushort4 v = __ldg(static_cast<const ushort4*>(p) + i);
    j[0] = v.x, j[1] = v.y, j[2] = v.z, j[3] = v.w;
  }
}

template <bool kUnorm>
__device__ __forceinline__ void load_weights(const void* p, std::size_t i, float w[4]) {
  if constexpr (kUnorm) {
    const ushort4 v = __ldg(static_cast<const ushort4*>(p) + i);
    constexpr float s = 1.0f / 65535.0f;
    w[0] = v.x * s, w[1] = v.y * s, w[2] = v.z * s, w[3] = v.w * s;
  } else {
    const float4 v = __ldg(static_cast<const float4*>(p) + i);
    w[0] = v.x, w[1] = v.y, w[2] = v.z, w[3] = v.w;
  }
}

// A motor's 12 blades (types.hpp order) in split form: G = a + b in s[0..3], H = a - b in s[4..7], the einf
// blades U in s[8..11].
// (rotor_sign.hpp, the one definition the CPU loops and the GLSL share.)
__device__ __forceinline__ void motor_split(const float c[12], float s[12]) { rotor_sign::split(c, s, s + 4, s + 8); }

// Row-major 3x4 (x, y, z, translation per row) for a motor in split form: the generated prepare of the
// staged transform_point_split (its prepared values are the rows as (translation, x, y, z); the host
// header skinning_palettes.hpp checks that layout at compile time).
__device__ __forceinline__ void split_rows(const float s[12], float m[12]) {
  float prepared[12];
  cga::kernels::transform_point_split_prepare(s, s + 4, s + 8, prepared);
  for (int r = 0; r < 3; ++r)
    m[4 * r] = prepared[4 * r + 1], m[4 * r + 1] = prepared[4 * r + 2], m[4 * r + 2] = prepared[4 * r + 3],
    m[4 * r + 3] = prepared[4 * r];
}

// The rotation (times |r|^2) and translation of an unnormalized dual-quaternion blend, as a 3x4 matrix
// divided by |r|^2 (the CPU dqs loop's formula).
__device__ __forceinline__ void dual_quat_rows(const float b[8], float m[12]) {
  const float rx = b[0], ry = b[1], rz = b[2], rw = b[3], dx = b[4], dy = b[5], dz = b[6], dw = b[7];
  const float inv = 1.0f / (rx * rx + ry * ry + rz * rz + rw * rw);
  const float diag = rw * rw - (rx * rx + ry * ry + rz * rz);
  m[0] = (diag + 2 * rx * rx) * inv, m[1] = 2 * (rx * ry - rw * rz) * inv, m[2] = 2 * (rx * rz + rw * ry) * inv;
  m[3] = 2.0f * (rw * dx - dw * rx + (ry * dz - rz * dy)) * inv;
  m[4] = 2 * (ry * rx + rw * rz) * inv, m[5] = (diag + 2 * ry * ry) * inv, m[6] = 2 * (ry * rz - rw * rx) * inv;
  m[7] = 2.0f * (rw * dy - dw * ry + (rz * dx - rx * dz)) * inv;
  m[8] = 2 * (rz * rx - rw * ry) * inv, m[9] = 2 * (rz * ry + rw * rx) * inv, m[10] = (diag + 2 * rz * rz) * inv;
  m[11] = 2.0f * (rw * dz - dw * rz + (rx * dy - ry * dx)) * inv;
}

// Stores entry `b` (kUnits 16-B units from v) into every copy. Lane-rotated copy order: the lanes of a warp
// store different copies at once, i.e. different bank groups.
template <int kUnits>
__device__ __forceinline__ void store_entry(float4* pal, unsigned b, const float* v, unsigned shift) {
  const unsigned copies = 1u << shift;
  for (int u = 0; u < kUnits; ++u) {
    const float4 x = make_float4(v[4 * u], v[4 * u + 1], v[4 * u + 2], v[4 * u + 3]);
    for (unsigned c = 0; c < copies; ++c)
      pal[palette_slot(b * kUnits + u, (c + b) & (copies - 1u), shift)] = x;
  }
}

// Entry j of this lane's copy into registers: kUnits 128-bit shared loads.
template <int kUnits>
__device__ __forceinline__ void load_entry(const float4* pal, int j, unsigned shift, unsigned copy,
                                           float out[4 * kUnits]) {
  for (int u = 0; u < kUnits; ++u) {
    const float4 x = pal[palette_slot(static_cast<unsigned>(j) * kUnits + u, copy, shift)];
    out[4 * u] = x.x, out[4 * u + 1] = x.y, out[4 * u + 2] = x.z, out[4 * u + 3] = x.w;
  }
}

// 8 blocks of 256 threads per SM (2048 threads, full occupancy on sm_90): caps registers at 32 (ptxas -v: no
// spills but 4 B in dqs with normals), and 8 x 24 KiB of palette copies fit in the SM's 228 KiB.
template <int kMethod, bool kU8, bool kUnorm, bool kNormals>
__global__ void __launch_bounds__(kBlock, 8) skin_kernel(const KernelArgs a) {
  constexpr int kEntry = kMethod == kDqs ? 8 : 12;
  constexpr int kUnits = kEntry / 4;
  extern __shared__ float4 palette[];
  const unsigned shift = a.copy_shift, copy = threadIdx.x & ((1u << shift) - 1u);
  const unsigned instance = a.instance_offset + blockIdx.y;
  const float* src = a.palettes + static_cast<std::size_t>(instance) * a.bones * kEntry;
  if constexpr (kMethod == kPoints) {
    for (unsigned b = threadIdx.x; b < a.bones; b += blockDim.x) {
      float motor[12], split[12], rows[12];
      for (int e = 0; e < 12; ++e) motor[e] = src[12 * b + e];
      motor_split(motor, split);
      split_rows(split, rows);
      store_entry<kUnits>(palette, b, rows, shift);
    }
  } else if constexpr (kMethod == kMotors) {
    for (unsigned b = threadIdx.x; b < a.bones; b += blockDim.x) {
      float motor[12], split[12];
      for (int e = 0; e < 12; ++e) motor[e] = src[12 * b + e];
      motor_split(motor, split);
      store_entry<kUnits>(palette, b, split, shift);
    }
  } else {
    // Consecutive threads fill consecutive slots (conflict-free stores); each reads its unit's 16 B.
    const float4* src4 = reinterpret_cast<const float4*>(src);
    const unsigned units = a.bones * kUnits, slots = palette_slots(units, shift);
    for (unsigned s = threadIdx.x; s < slots; s += blockDim.x) {
      const unsigned unit = palette_unit_of_slot(s, shift);
      if (unit < units) palette[s] = __ldg(src4 + unit);
    }
  }
  __syncthreads();

  const std::size_t in_base = a.per_instance_inputs ? static_cast<std::size_t>(instance) * a.vertex_count : 0;
  const std::size_t out_base = static_cast<std::size_t>(instance) * a.vertex_count;
  for (unsigned v = blockIdx.x * blockDim.x + threadIdx.x; v < a.vertex_count; v += gridDim.x * blockDim.x) {
    const std::size_t iv = in_base + v, ov = out_base + v;
    const float x = __ldg(a.positions + 3 * iv), y = __ldg(a.positions + 3 * iv + 1),
                z = __ldg(a.positions + 3 * iv + 2);
    int j[4];
    float w[4];
    load_joints<kU8>(a.joints, iv, j);
    load_weights<kUnorm>(a.weights, iv, w);
    float m[12] = {};  // the blended 3x4
    float px = 0.0f, py = 0.0f, pz = 0.0f;
    if constexpr (kMethod == kLbs || kMethod == kPoints) {
      float q[12];
      load_entry<3>(palette, j[0], shift, copy, q);
      for (int e = 0; e < 12; ++e) m[e] = w[0] * q[e];
      for (int k = 1; k < 4; ++k) {
        load_entry<3>(palette, j[k], shift, copy, q);
        for (int e = 0; e < 12; ++e) m[e] += w[k] * q[e];
      }
    } else if constexpr (kMethod == kDqs) {
      float q0[8], q[8];
      load_entry<2>(palette, j[0], shift, copy, q0);
      float b[8];
      for (int e = 0; e < 8; ++e) b[e] = w[0] * q0[e];
      for (int k = 1; k < 4; ++k) {
        load_entry<2>(palette, j[k], shift, copy, q);
        const float dot = q0[0] * q[0] + q0[1] * q[1] + q0[2] * q[2] + q0[3] * q[3];
        const float wk = copysignf(w[k], dot);
        for (int e = 0; e < 8; ++e) b[e] += wk * q[e];
      }
      dual_quat_rows(b, m);
    } else {  // kMotors
      float q0[12], q[12];
      load_entry<3>(palette, j[0], shift, copy, q0);
      float b[12];
      for (int e = 0; e < 12; ++e) b[e] = w[0] * q0[e];
      for (int k = 1; k < 4; ++k) {
        load_entry<3>(palette, j[k], shift, copy, q);
        // Rotor parts times 1 + k: G (split indices 0-3).
        const float wk = rotor_sign::signed_weight(w[k], rotor_sign::dot(q0, q));
        for (int e = 0; e < 12; ++e) b[e] += wk * q[e];
      }
      split_rows(b, m);
    }
    px = m[0] * x + m[1] * y + m[2] * z + m[3];
    py = m[4] * x + m[5] * y + m[6] * z + m[7];
    pz = m[8] * x + m[9] * y + m[10] * z + m[11];
    a.out_positions[3 * ov] = px;
    a.out_positions[3 * ov + 1] = py;
    a.out_positions[3 * ov + 2] = pz;
    if constexpr (kNormals) {
      const float nx = __ldg(a.normals + 3 * iv), ny = __ldg(a.normals + 3 * iv + 1), nz = __ldg(a.normals + 3 * iv + 2);
      float ox = m[0] * nx + m[1] * ny + m[2] * nz;
      float oy = m[4] * nx + m[5] * ny + m[6] * nz;
      float oz = m[8] * nx + m[9] * ny + m[10] * nz;
      const float inv = rsqrtf(ox * ox + oy * oy + oz * oz);
      a.out_normals[3 * ov] = ox * inv;
      a.out_normals[3 * ov + 1] = oy * inv;
      a.out_normals[3 * ov + 2] = oz * inv;
    }
  }
}

using Kernel = void (*)(KernelArgs);

template <int kMethod>
Kernel pick(bool u8, bool unorm, bool normals) {
  if (u8) {
    if (unorm) return normals ? skin_kernel<kMethod, true, true, true> : skin_kernel<kMethod, true, true, false>;
    return normals ? skin_kernel<kMethod, true, false, true> : skin_kernel<kMethod, true, false, false>;
  }
  if (unorm) return normals ? skin_kernel<kMethod, false, true, true> : skin_kernel<kMethod, false, true, false>;
  return normals ? skin_kernel<kMethod, false, false, true> : skin_kernel<kMethod, false, false, false>;
}

}  // namespace

std::string launch(const LaunchArgs& args, void* stream) {
  const bool normals = args.normals != nullptr;
  Kernel kernel = nullptr;
  switch (args.method) {
    case kLbs: kernel = pick<kLbs>(args.joints_u8, args.weights_unorm16, normals); break;
    case kDqs: kernel = pick<kDqs>(args.joints_u8, args.weights_unorm16, normals); break;
    case kPoints: kernel = pick<kPoints>(args.joints_u8, args.weights_unorm16, normals); break;
    case kMotors: kernel = pick<kMotors>(args.joints_u8, args.weights_unorm16, normals); break;
    default: return "unknown method " + std::to_string(args.method);
  }
  const unsigned units = palette_units(args.method);
  const unsigned shift = copy_shift_for(args.bones, units);
  KernelArgs k{static_cast<unsigned>(args.vertex_count), static_cast<unsigned>(args.bones), 0, shift,
               args.per_instance_inputs, args.positions, args.normals, args.joints, args.weights,
               args.palettes, args.out_positions, args.out_normals};
  const std::size_t shared = std::size_t{palette_slots(static_cast<unsigned>(args.bones) * units, shift)} * 16u;
  const std::size_t per_block = static_cast<std::size_t>(kBlock) * kVerticesPerThread;
  const unsigned blocks_x = static_cast<unsigned>((args.vertex_count + per_block - 1) / per_block);
  auto s = static_cast<cudaStream_t>(stream);
  // gridDim.y is limited to 65535: larger crowds go in several launches.
  for (std::size_t first = 0; first < args.instances; first += 65535) {
    const std::size_t count = args.instances - first < 65535 ? args.instances - first : 65535;
    k.instance_offset = static_cast<unsigned>(first);
    kernel<<<dim3(blocks_x, static_cast<unsigned>(count)), kBlock, shared, s>>>(k);
    const cudaError_t e = cudaGetLastError();
    if (e != cudaSuccess) return cudaGetErrorString(e);
  }
  return {};
}

}  // namespace cga::cuda::detail
