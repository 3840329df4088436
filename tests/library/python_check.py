"""python_check.py LIBRARY_PY IN OUT: python_check's runner. Evaluates the cases of IN with the generated Python
library (cgagen --library --target python) and writes their values to OUT.

IN, per case: a line `case OP A B RESULT ROWS` (B is - for a unary operation), then ROWS lines of operand
coefficients (a's, then b's). OUT, per case: a line `forms F1 F2 ...`, then per row the values of every form
in that order. The forms: the module function OP(a, b) (for OP `matrix`, matrix(a, B)(b)) on all rows at once (float32 arrays of shape (N, ROWS)),
the method a.OP() of a unary operation, the operator where the library gives the operation one (also all rows
at once), and the module function on each row alone in float64 (`single`: the unbatched path). A result of
another class or dtype than the registry's fails the run.
"""
import importlib.util
import operator
import sys

import numpy as np

# The Python operator of each operation that has one (dual's ! has no Python counterpart).
OPERATORS = {"gp": operator.mul, "outer": operator.xor, "inner": operator.or_, "rp": operator.and_,
             "add": operator.add, "sub": operator.sub, "neg": operator.neg, "reverse": operator.invert}


def load(path):
    spec = importlib.util.spec_from_file_location("library", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def checked(value, cls, dtype, what):
    if type(value) is not cls or value.v.dtype != dtype:
        sys.exit(f"python_check: {what} gave {type(value).__name__} of {value.v.dtype}, not {cls.__name__} of {dtype}")
    return value


def main():
    lib = load(sys.argv[1])
    lines = open(sys.argv[2]).read().splitlines()
    out = []
    i = 0
    while i < len(lines):
        _, op, a, b, result, rows = lines[i].split()
        rows = int(rows)
        x = np.array([[float(w) for w in line.split()] for line in lines[i + 1:i + 1 + rows]], dtype=np.float32)
        i += 1 + rows
        ta, tr = lib.TYPES[a], lib.TYPES[result]
        na = len(ta.blades)
        operands = [ta(x[:, :na].T)] + ([lib.TYPES[b](x[:, na:].T)] if b != "-" else [])
        what = f"{op}({a}{', ' + b if b != '-' else ''})"
        if op == "matrix":  # the matrix of a's sandwich on b's class, applied to b
            def call(x, y):
                return lib.matrix(x, type(y))(y)
        else:
            call = getattr(lib, op)
        forms, values = ["function"], [call(*operands)]
        if len(operands) == 1:
            forms.append("method")
            values.append(getattr(operands[0], op)())
        if op in OPERATORS:
            forms.append("operator")
            values.append(OPERATORS[op](*operands))
        values = [checked(v, tr, np.float32, what + " as " + f).v for f, v in zip(forms, values)]
        forms.append("single")
        out.append("forms " + " ".join(forms))
        for row in range(rows):
            alone = [type(o)(o.v[:, row].astype(np.float64)) for o in operands]
            single = checked(call(*alone), tr, np.float64, what + " single").v
            row_values = [w[:, row] for w in values] + [single]
            out.append(" ".join(repr(float(c)) for w in row_values for c in w))
    open(sys.argv[3], "w").write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
