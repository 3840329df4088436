// Runs a cgagen javascript kernel: node drive.mjs META MODULE IN OUT. Calls NAME(...inputs) per input row
// (a staged kernel: NAME_prepare on the uniform inputs, then NAME)
// (a multivector input as an array of its blades) and writes the flat outputs one row per line; checks the
// interface (an array of outputs, each an array of the declared number of numbers).
import { readFileSync, writeFileSync } from "node:fs";
import { pathToFileURL } from "node:url";

const [meta_path, module_path, in_path, out_path] = process.argv.slice(2);
const meta = JSON.parse(readFileSync(meta_path, "utf8"));
const mod = await import(pathToFileURL(module_path).href);
const body = mod[meta.fn];  // the function as JavaScript spells it (a reserved word gets a trailing _)
if (typeof body !== "function") throw new Error(`no function ${meta.fn}`);
// A staged kernel (meta.prepared = K > 0): NAME_prepare(uniform inputs) -> [prepared (K values)], then
// NAME(prepared, other inputs).
const prepare = meta.prepared ? mod[meta.prepare] : null;
if (meta.prepared && typeof prepare !== "function") throw new Error(`no function ${meta.prepare}`);
const fn = !meta.prepared ? body : (...args) => {
  const p = prepare(...args.filter((_, i) => meta.uniform[i]));
  if (!Array.isArray(p) || p.length !== 1 || p[0].length !== meta.prepared) throw new Error("bad prepare output");
  return body(p[0], ...args.filter((_, i) => !meta.uniform[i]));
};
const lines = readFileSync(in_path, "utf8").split("\n").filter((l) => l.length > 0);
const out = [];
for (const line of lines) {
  const v = line.split(" ").map(Number);
  const args = [];
  let off = 0;
  for (const n of meta.inputs) {
    if (n === 0) args.push(v[off++]);
    else { args.push(v.slice(off, off + n)); off += n; }
  }
  const res = fn(...args);
  if (!Array.isArray(res) || res.length !== meta.outputs.length) throw new Error("bad outputs");
  const row = [];
  res.forEach((o, i) => {
    if (!Array.isArray(o) || o.length !== meta.outputs[i]) throw new Error(`bad output ${i}`);
    for (const x of o) {
      if (typeof x !== "number") throw new Error("not a number");
      row.push(String(x));
    }
  });
  out.push(row.join(" "));
}
writeFileSync(out_path, out.join("\n") + "\n");
