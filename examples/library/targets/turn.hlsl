// The generated pga3 library in HLSL (cgagen --library --target hlsl): a compute shader turning points about
// the x axis. The shader's text is pga3.hlsl, then this. HLSL reserves `line` and `point`: the types are
// pga3_line_ and pga3_point_.
RWStructuredBuffer<float4> points : register(u0);
cbuffer Params : register(b0) { float angle; };

pga3_point_ turn(pga3_point_ p, float a) {
  pga3_line_ axis = {{0.0, 0.0, 0.0, 1.0, 0.0, 0.0}};  // e2^e3: the x axis
  pga3_motor m = pga3_exp(pga3_scale(0.5 * a, axis));   // overloaded on the operand types
  return pga3_sandwich(m, p);                           // m p ~m
}

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
  pga3_point_ p = {{points[id.x].x, points[id.x].y, points[id.x].z, points[id.x].w}};
  pga3_point_ q = turn(p, angle);
  points[id.x] = float4(q.v[0], q.v[1], q.v[2], q.v[3]);
}
