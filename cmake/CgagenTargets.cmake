# The targets of cgagen and their file extensions, for cgagen_generate(). Mirrors the table in
# gen/emit/targets.cpp (`cgagen --target list`, `cgagen --target-extension NAME`); the test
# targets/table_matches_tool fails when the two differ.
set(CGAGEN_TARGETS cpp simd glsl cuda hlsl glsl-es wgsl opencl python javascript rust latex dot)
set(CGAGEN_EXT_cpp .hpp)
set(CGAGEN_EXT_simd .simd.hpp)
set(CGAGEN_EXT_glsl .glsl)
set(CGAGEN_EXT_cuda .cuh)
set(CGAGEN_EXT_hlsl .hlsl)
set(CGAGEN_EXT_glsl-es .essl)
set(CGAGEN_EXT_wgsl .wgsl)
set(CGAGEN_EXT_opencl .cl)
set(CGAGEN_EXT_python .py)
set(CGAGEN_EXT_javascript .mjs)
set(CGAGEN_EXT_rust .rs)
set(CGAGEN_EXT_latex .tex)
set(CGAGEN_EXT_dot .dot)
