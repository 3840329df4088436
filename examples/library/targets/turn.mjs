// The generated pga3 library in JavaScript (cgagen --library --target javascript, an ES module) in node:
// node turn.mjs path/to/pga3.mjs turns points about the x axis and checks them against plain trigonometry.
// Exit status 0 when every point agrees within 1e-12 (the module computes in double).
import { pathToFileURL } from "node:url";

const pga3 = await import(pathToFileURL(process.argv[2]).href);
const angle = 0.7;
const axis = new pga3.Line([0, 0, 0, 1, 0, 0]);          // e2^e3: the x axis
const m = axis.scale(0.5 * angle).exp();                 // a motor: rotation by `angle` about it
let worst = 0;
for (let i = 0; i < 16; ++i) {
  const [x, y, z] = [Math.sin(0.3 * i), 0.1 * i - 3, Math.cos(0.7 * i)];
  const q = pga3.ops.sandwich(m, new pga3.Point([-x, y, -z, 1]));  // (x, y, z) = -x e0^e2^e3 + y e0^e1^e3 - z e0^e1^e2 + e1^e2^e3
  const got = [-q.v[0] / q.v[3], q.v[1] / q.v[3], -q.v[2] / q.v[3]];
  const c = Math.cos(angle), s = Math.sin(angle);
  const want = [x, c * y + s * z, c * z - s * y];        // as examples/library/main.cpp: from z towards y
  for (let k = 0; k < 3; ++k) worst = Math.max(worst, Math.abs(got[k] - want[k]));
}
console.log(`pga3 library in JavaScript: 16 points turned about x; off by ${worst.toExponential(3)}`);
process.exit(worst < 1e-12 ? 0 : 1);
