// The words each target's identifiers must avoid (emit/names.hpp): the language's keywords and reserved
// words, plus the names a generated file itself relies on inside a kernel (std, Math, Array, _np, the math
// functions a target calls unqualified, the type names it declares with, macros of the headers it
// includes). A script name in this list is spelt with a trailing underscore (docs/generator.md, "Names").
#include <sstream>

#include "emit/names.hpp"

namespace cgagen::emit {

namespace {

void add(std::set<std::string>& s, const char* words) {
  std::istringstream in(words);
  for (std::string w; in >> w;) s.insert(w);
}

// C and C++ (C++20 keywords, alternative tokens, C keywords, <cmath>/<math.h> macros glibc defines).
const char* kC =
    "alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t char16_t char32_t class "
    "compl concept const consteval constexpr constinit const_cast continue co_await co_return co_yield decltype "
    "default delete do double dynamic_cast else enum explicit export extern false float for friend goto if inline "
    "int long mutable namespace new noexcept not not_eq nullptr operator or or_eq private protected public "
    "register reinterpret_cast requires return short signed sizeof static static_assert static_cast struct "
    "switch template this thread_local throw true try typedef typeid typename union unsigned using virtual void "
    "volatile wchar_t while xor xor_eq restrict _Alignas _Alignof _Atomic _Bool _Complex _Generic _Imaginary "
    "_Noreturn _Static_assert _Thread_local NULL std cga kernels override final import module "
    "M_E M_LOG2E M_LOG10E M_LN2 M_LN10 M_PI M_PI_2 M_PI_4 M_1_PI M_2_PI M_2_SQRTPI M_SQRT2 M_SQRT1_2 "
    "INFINITY NAN HUGE_VAL HUGE_VALF HUGE_VALL FP_NAN FP_INFINITE FP_ZERO FP_SUBNORMAL FP_NORMAL "
    "FP_ILOGB0 FP_ILOGBNAN MATH_ERRNO MATH_ERREXCEPT math_errhandling errno assert EOF";
// The macros g++ 12 / glibc 2.36 (Debian 12) define for <cmath>, <array> and <string_view>, the headers of
// the cpp and cuda files: `g++ -std=c++17 -dM -E` over them, names not starting with _.
const char* kGlibcMacros =
    "BIG_ENDIAN BYTE_ORDER EXIT_FAILURE EXIT_SUCCESS FD_CLR FD_ISSET FD_SET FD_SETSIZE FD_ZERO FP_ILOGB0  "
    "FP_ILOGBNAN FP_INFINITE FP_INT_DOWNWARD FP_INT_TONEAREST FP_INT_TONEARESTFROMZERO FP_INT_TOWARDZERO  "
    "FP_INT_UPWARD FP_LLOGB0 FP_LLOGBNAN FP_NAN FP_NORMAL FP_SUBNORMAL FP_ZERO HUGE_VAL HUGE_VALF HUGE_VALL  "
    "HUGE_VAL_F128 HUGE_VAL_F32 HUGE_VAL_F32X HUGE_VAL_F64 HUGE_VAL_F64X INFINITY INT16_C INT16_MAX  "
    "INT16_MIN INT16_WIDTH INT32_C INT32_MAX INT32_MIN INT32_WIDTH INT64_C INT64_MAX INT64_MIN INT64_WIDTH  "
    "INT8_C INT8_MAX INT8_MIN INT8_WIDTH INTMAX_C INTMAX_MAX INTMAX_MIN INTMAX_WIDTH INTPTR_MAX INTPTR_MIN  "
    "INTPTR_WIDTH INT_FAST16_MAX INT_FAST16_MIN INT_FAST16_WIDTH INT_FAST32_MAX INT_FAST32_MIN  "
    "INT_FAST32_WIDTH INT_FAST64_MAX INT_FAST64_MIN INT_FAST64_WIDTH INT_FAST8_MAX INT_FAST8_MIN  "
    "INT_FAST8_WIDTH INT_LEAST16_MAX INT_LEAST16_MIN INT_LEAST16_WIDTH INT_LEAST32_MAX INT_LEAST32_MIN  "
    "INT_LEAST32_WIDTH INT_LEAST64_MAX INT_LEAST64_MIN INT_LEAST64_WIDTH INT_LEAST8_MAX INT_LEAST8_MIN  "
    "INT_LEAST8_WIDTH LITTLE_ENDIAN MATH_ERREXCEPT MATH_ERRNO MAXFLOAT MB_CUR_MAX M_1_PI M_1_PIf M_1_PIf128  "
    "M_1_PIf32 M_1_PIf32x M_1_PIf64 M_1_PIf64x M_1_PIl M_2_PI M_2_PIf M_2_PIf128 M_2_PIf32 M_2_PIf32x  "
    "M_2_PIf64 M_2_PIf64x M_2_PIl M_2_SQRTPI M_2_SQRTPIf M_2_SQRTPIf128 M_2_SQRTPIf32 M_2_SQRTPIf32x  "
    "M_2_SQRTPIf64 M_2_SQRTPIf64x M_2_SQRTPIl M_E M_Ef M_Ef128 M_Ef32 M_Ef32x M_Ef64 M_Ef64x M_El M_LN10  "
    "M_LN10f M_LN10f128 M_LN10f32 M_LN10f32x M_LN10f64 M_LN10f64x M_LN10l M_LN2 M_LN2f M_LN2f128 M_LN2f32  "
    "M_LN2f32x M_LN2f64 M_LN2f64x M_LN2l M_LOG10E M_LOG10Ef M_LOG10Ef128 M_LOG10Ef32 M_LOG10Ef32x  "
    "M_LOG10Ef64 M_LOG10Ef64x M_LOG10El M_LOG2E M_LOG2Ef M_LOG2Ef128 M_LOG2Ef32 M_LOG2Ef32x M_LOG2Ef64  "
    "M_LOG2Ef64x M_LOG2El M_PI M_PI_2 M_PI_2f M_PI_2f128 M_PI_2f32 M_PI_2f32x M_PI_2f64 M_PI_2f64x M_PI_2l  "
    "M_PI_4 M_PI_4f M_PI_4f128 M_PI_4f32 M_PI_4f32x M_PI_4f64 M_PI_4f64x M_PI_4l M_PIf M_PIf128 M_PIf32  "
    "M_PIf32x M_PIf64 M_PIf64x M_PIl M_SQRT1_2 M_SQRT1_2f M_SQRT1_2f128 M_SQRT1_2f32 M_SQRT1_2f32x  "
    "M_SQRT1_2f64 M_SQRT1_2f64x M_SQRT1_2l M_SQRT2 M_SQRT2f M_SQRT2f128 M_SQRT2f32 M_SQRT2f32x M_SQRT2f64  "
    "M_SQRT2f64x M_SQRT2l NAN NFDBITS NULL PDP_ENDIAN PTRDIFF_MAX PTRDIFF_MIN PTRDIFF_WIDTH RAND_MAX  "
    "SIG_ATOMIC_MAX SIG_ATOMIC_MIN SIG_ATOMIC_WIDTH SIZE_MAX SIZE_WIDTH SNAN SNANF SNANF128 SNANF32 SNANF32X  "
    "SNANF64 SNANF64X SNANL UINT16_C UINT16_MAX UINT16_WIDTH UINT32_C UINT32_MAX UINT32_WIDTH UINT64_C  "
    "UINT64_MAX UINT64_WIDTH UINT8_C UINT8_MAX UINT8_WIDTH UINTMAX_C UINTMAX_MAX UINTMAX_WIDTH UINTPTR_MAX  "
    "UINTPTR_WIDTH UINT_FAST16_MAX UINT_FAST16_WIDTH UINT_FAST32_MAX UINT_FAST32_WIDTH UINT_FAST64_MAX  "
    "UINT_FAST64_WIDTH UINT_FAST8_MAX UINT_FAST8_WIDTH UINT_LEAST16_MAX UINT_LEAST16_WIDTH UINT_LEAST32_MAX  "
    "UINT_LEAST32_WIDTH UINT_LEAST64_MAX UINT_LEAST64_WIDTH UINT_LEAST8_MAX UINT_LEAST8_WIDTH WCHAR_MAX  "
    "WCHAR_MIN WCHAR_WIDTH WCONTINUED WEOF WEXITED WEXITSTATUS WIFCONTINUED WIFEXITED WIFSIGNALED WIFSTOPPED  "
    "WINT_MAX WINT_MIN WINT_WIDTH WNOHANG WNOWAIT WSTOPPED WSTOPSIG WTERMSIG WUNTRACED alloca be16toh  "
    "be32toh be64toh htobe16 htobe32 htobe64 htole16 htole32 htole64 issubnormal le16toh le32toh le64toh  "
    "math_errhandling";
// Math functions a target may call unqualified; a parameter of the same name would hide them.
const char* kMath =
    "sqrt pow sin cos tan asin acos atan atan2 exp log abs fabs sinh cosh tanh floor ceil min max select "
    "inversesqrt rsqrt clamp sign fract mod fmod";
const char* kCuda =
    "__host__ __device__ __global__ __forceinline__ __shared__ __constant__ __restrict__ warpSize threadIdx "
    "blockIdx blockDim gridDim";
// GLSL 4.60 and GLSL ES 3.00: keywords, reserved words and the built-in types.
const char* kGlsl =
    "attribute const uniform varying buffer shared coherent volatile restrict readonly writeonly atomic_uint "
    "layout centroid flat smooth noperspective patch sample break continue do for while switch case default if "
    "else subroutine in out inout float double int void bool true false invariant precise discard return "
    "lowp mediump highp precision struct common partition active asm class union enum typedef template this "
    "resource goto inline noinline public static extern external interface long short half fixed unsigned "
    "superp input output filter sizeof cast namespace using sampler3DRect main gl_Position uint row_major "
    "column_major packed std140 std430 shared demote";
const char* kHlsl =
    "AppendStructuredBuffer asm asm_fragment BlendState bool break Buffer ByteAddressBuffer case cbuffer "
    "centroid class column_major compile compile_fragment CompileShader const continue ComputeShader "
    "ConsumeStructuredBuffer default DepthStencilState DepthStencilView discard do double DomainShader dword "
    "else export extern false float for fxgroup GeometryShader groupshared half Hullshader HullShader if in "
    "inline inout InputPatch int interface line lineadj linear LineStream matrix min16float min10float min16int "
    "min12int min16uint namespace nointerpolation noperspective NULL out OutputPatch packoffset pass pixelfragment "
    "PixelShader point PointStream precise RasterizerState RenderTargetView return register row_major RWBuffer "
    "RWByteAddressBuffer RWStructuredBuffer RWTexture1D RWTexture1DArray RWTexture2D RWTexture2DArray "
    "RWTexture3D sample sampler SamplerState SamplerComparisonState shared snorm stateblock stateblock_state "
    "static string struct switch StructuredBuffer tbuffer technique technique10 technique11 texture Texture "
    "Texture1D Texture1DArray Texture2D Texture2DArray Texture2DMS Texture2DMSArray Texture3D TextureCube "
    "TextureCubeArray true typedef triangle triangleadj TriangleStream uint uniform unorm unsigned vector "
    "vertexfragment VertexShader void volatile while auto case catch char const_cast delete dynamic_cast enum "
    "explicit friend goto long mutable new operator private protected public reinterpret_cast short signed "
    "sizeof static_cast template this throw try typename union using virtual layout sampler1D sampler2D "
    "sampler3D samplerCUBE sampler_state texture1D texture2D texture3D textureCUBE ConstantBuffer TextureBuffer "
    "RasterizerOrderedBuffer RasterizerOrderedByteAddressBuffer RasterizerOrderedStructuredBuffer "
    "RasterizerOrderedTexture1D RasterizerOrderedTexture1DArray RasterizerOrderedTexture2D "
    "RasterizerOrderedTexture2DArray RasterizerOrderedTexture3D SubpassInput SubpassInputMS globallycoherent";
const char* kOpenCl =
    "__kernel kernel __global global __local local __constant constant __private private __read_only read_only "
    "__write_only write_only __read_write read_write uchar ushort uint ulong half quad bool image2d_t image3d_t "
    "image2d_array_t image1d_t image1d_buffer_t image1d_array_t sampler_t event_t size_t ptrdiff_t intptr_t "
    "uintptr_t complex imaginary MAXFLOAT HUGE_VALF INFINITY NAN FLT_MAX FLT_MIN FLT_EPSILON DBL_MAX DBL_MIN "
    "DBL_EPSILON M_E_F M_PI_F M_PI_2_F M_PI_4_F M_1_PI_F M_2_PI_F M_SQRT2_F M_LN2_F M_LN10_F";
const char* kPython =
    "False None True and as assert async await break class continue def del elif else except finally for from "
    "global if import in is lambda nonlocal not or pass raise return try while with yield match case type "
    "_np _shape _out _s";
const char* kJs =
    "await break case catch class const continue debugger default delete do else enum export extends false "
    "finally for function if implements import in instanceof interface let new null package private protected "
    "public return static super switch this throw true try typeof var void while with yield arguments eval "
    "Math Array undefined NaN Infinity";
const char* kRust =
    "as async await break const continue crate dyn else enum extern false fn for if impl in let loop match mod "
    "move mut pub ref return self Self static struct super trait true type unsafe use where while abstract "
    "become box do final macro override priv try typeof unsized virtual yield union _ f32 f64 "
    // The prelude: a variant or constant as a parameter name is a pattern, not a new binding.
    "None Some Ok Err Option Result Box String Vec ToString ToOwned Copy Clone Default Drop Eq PartialEq Ord "
    "PartialOrd Fn FnMut FnOnce Send Sized Sync Unpin Iterator IntoIterator Extend From Into AsRef AsMut";

// WGSL keywords and reserved words (WGSL spec, sections 15.1 and 15.2).
const char* kWgslReserved =
    "alias break case const const_assert continue continuing default diagnostic discard else enable "
    "false fn for if let loop override requires return struct switch true var while NULL Self abstract "
    "active alignas alignof as asm asm_fragment async attribute auto await become binding_array cast "
    "catch class co_await co_return co_yield coherent column_major common compile compile_fragment "
    "concept const_cast consteval constexpr constinit crate debugger decltype delete demote "
    "demote_to_helper do dynamic_cast enum explicit export extends extern external fallthrough filter "
    "final finally friend from fxgroup get goto groupshared highp impl implements import inline "
    "instanceof interface layout lowp macro macro_rules match mediump meta mod module move mut mutable "
    "namespace new nil noexcept noinline nointerpolation non_coherent noncoherent noperspective null "
    "nullptr of operator package packoffset partition pass patch pixelfragment precise precision "
    "premerge priv protected pub public readonly ref regardless register reinterpret_cast require "
    "resource restrict self set shared sizeof smooth snorm static static_assert static_cast std "
    "subroutine super target template this thread_local throw trait try type typedef typeid typename "
    "typeof union unless unorm unsafe unsized use using varying virtual volatile wgsl where with "
    "writeonly yield ";

// Vector and matrix type names: PREFIX + 2..4, and PREFIX + NxM.
void add_vectors(std::set<std::string>& s, const char* prefixes, bool matrices) {
  std::istringstream in(prefixes);
  for (std::string p; in >> p;)
    for (int n = 1; n <= 4; ++n) {
      if (n > 1 || matrices) s.insert(p + std::to_string(n));
      if (matrices)
        for (int m = 1; m <= 4; ++m) s.insert(p + std::to_string(n) + "x" + std::to_string(m));
    }
}

}  // namespace

std::set<std::string> reserved_words(const std::string& target) {
  std::set<std::string> s;
  if (target == "cpp" || target == "cuda" || target == "opencl" || target == "simd") add(s, kC);
  if (target == "cpp" || target == "cuda" || target == "simd") add(s, kGlibcMacros);
  // simd: what its kernels and batch entries name (the tag d, its types, the namespaces, loop counters).
  if (target == "simd") add(s, "d D V hn hwy simd In Out i n k N");
  if (target == "cuda") add(s, kCuda);
  if (target == "glsl" || target == "glsl-es") {
    add(s, kGlsl);
    add_vectors(s, "vec ivec uvec bvec dvec hvec fvec", false);
    add_vectors(s, "mat dmat", false);
    for (int n = 2; n <= 4; ++n)
      for (int m = 2; m <= 4; ++m) s.insert("mat" + std::to_string(n) + "x" + std::to_string(m)),
                                   s.insert("dmat" + std::to_string(n) + "x" + std::to_string(m));
    for (const char* t : {"sampler", "isampler", "usampler", "image", "iimage", "uimage"})
      for (const char* d : {"1D", "2D", "3D", "Cube", "2DRect", "1DArray", "2DArray", "CubeArray", "Buffer",
                            "2DMS", "2DMSArray"})
        s.insert(std::string(t) + d);
    for (const char* d : {"1DShadow", "2DShadow", "2DRectShadow", "1DArrayShadow", "2DArrayShadow",
                          "CubeShadow", "CubeArrayShadow", "3DRect"})
      s.insert(std::string("sampler") + d);
  }
  if (target == "hlsl") {
    add(s, kHlsl);
    add_vectors(s, "bool int uint dword half float double min16float min10float min16int min12int min16uint", true);
  }
  if (target == "opencl") {
    add(s, kOpenCl);
    add_vectors(s, "char uchar short ushort int uint long ulong float double half", false);
    for (const char* p : {"char", "uchar", "short", "ushort", "int", "uint", "long", "ulong", "float", "double", "half"}) {
      s.insert(std::string(p) + "8");
      s.insert(std::string(p) + "16");
    }
  }
  if (target == "wgsl") {
    add(s, kWgslReserved);
    add(s, "_ f16 f32 i32 u32 bool array atomic mat2x2 mat2x3 mat2x4 mat3x2 mat3x3 mat3x4 mat4x2 mat4x3 mat4x4 "
           "ptr sampler sampler_comparison vec2 vec3 vec4 function private workgroup uniform storage read write "
           "read_write bitcast");
  }
  if (target == "python") add(s, kPython);
  if (target == "javascript") add(s, kJs);
  if (target == "rust") add(s, kRust);
  if (target == "cuda" || target == "opencl" || target == "glsl" || target == "glsl-es" || target == "hlsl" ||
      target == "wgsl")
    add(s, kMath);
  return s;
}

}  // namespace cgagen::emit
