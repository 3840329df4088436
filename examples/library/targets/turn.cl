// The generated pga3 library in OpenCL C (cgagen --library --target opencl): a kernel turning points about
// the x axis. The program's source is pga3.cl, then this. OpenCL C has no overloading: the operand types
// are part of each function's name.
__kernel void turn(__global const pga3_point* p, __global pga3_point* q, float angle) {
  const size_t i = get_global_id(0);
  const pga3_line axis = {{0, 0, 0, 1, 0, 0}};          // e2^e3: the x axis
  const pga3_motor m = pga3_exp_line(pga3_scale_line(0.5f * angle, axis));
  q[i] = pga3_sandwich_motor_point(m, p[i]);            // m p ~m
}
