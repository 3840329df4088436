// js_check.mjs LIBRARY_MJS IN OUT: js_check's runner. Evaluates the cases of IN with the generated JavaScript
// library (cgagen --library --target javascript) and writes their values to OUT.
//
// IN, per case: a line `case OP A B RESULT ROWS` (B is - for a unary operation), then ROWS lines of operand
// coefficients (a's, then b's). OUT, per case: a line `forms F1 F2 ...`, then per row the values of every form
// in that order. The forms: ops.OP(a, b), the method a.OP(b), and the exported kernel OP_A_B on the arrays (for
// OP `matrix`, the one form matrix(a, B).apply(b)). A result of another class than the registry's fails the run.
import { readFileSync, writeFileSync } from "node:fs";
import { pathToFileURL } from "node:url";

const [libraryPath, inPath, outPath] = process.argv.slice(2);
const lib = await import(pathToFileURL(libraryPath).href);
const lines = readFileSync(inPath, "utf8").split("\n");
const out = [];
for (let i = 0; i < lines.length && lines[i]; ) {
  const [, op, a, b, result, rowsText] = lines[i].split(" ");
  const rows = Number(rowsText);
  const ta = lib.TYPES[a], tb = b === "-" ? null : lib.TYPES[b], tr = lib.TYPES[result];
  if (op === "matrix") {  // the matrix of a's sandwich on b's class, applied to b
    out.push("forms apply");
    for (let row = 0; row < rows; ++row) {
      const x = lines[i + 1 + row].split(" ").map(Number);
      const v = lib.matrix(new ta(x.slice(0, ta.blades.length)), tb).apply(new tb(x.slice(ta.blades.length)));
      if (!(v instanceof tr)) throw new Error(`js_check: matrix(${a}, ${b}) gave ${v.constructor.name}, not ${tr.name}`);
      out.push(v.v.map((c) => String(c)).join(" "));
    }
    i += 1 + rows;
    continue;
  }
  const entry = lib.FUNCTIONS.find((f) => f[0] === op && f[1] === a && f[2] === (tb ? b : ""));
  if (!ta || !tr || (b !== "-" && !tb) || !entry || entry[3] !== result) {
    throw new Error(`js_check: ${op}(${a}, ${b}) -> ${result} is not in the library's registry`);
  }
  out.push("forms function method kernel");
  for (let row = 0; row < rows; ++row) {
    const x = lines[i + 1 + row].split(" ").map(Number);
    const na = ta.blades.length;
    const operands = [new ta(x.slice(0, na))].concat(tb ? [new tb(x.slice(na))] : []);
    const values = [lib.ops[op](...operands), operands[0][op](...operands.slice(1))];
    for (const v of values) {
      if (!(v instanceof tr)) throw new Error(`js_check: ${op}(${a}, ${b}) gave ${v.constructor.name}, not ${tr.name}`);
    }
    const kernel = entry[4](...operands.map((o) => o.v))[0];
    out.push(values.map((v) => v.v).concat([kernel]).flat().map((c) => String(c)).join(" "));
  }
  i += 1 + rows;
}
writeFileSync(outPath, out.join("\n") + "\n");
