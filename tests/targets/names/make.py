#!/usr/bin/env python3
"""Writes keywords_K.clu: every reserved word of every target (one per line on stdin, as printed by
`gen_test_names "[.print-words]"`) is an input of one script and an output of the next. scripts of at most 52
words each: WebGL 2 captures at most 15 vec4 varyings, so a script has at most 60 output blades."""
import re
import sys

words = sorted({w.strip() for w in sys.stdin if re.fullmatch(r"[A-Za-z_]\w*", w.strip())})  # not Catch2's lines
m = -(-len(words) // 52)  # scripts of at most 52 words
chunks = [words[i * len(words) // m:(i + 1) * len(words) // m] for i in range(m)]
for k in range(m):
    ins, outs = chunks[k], chunks[(k + 1) % m]
    lines = ["// Names test (tests/targets): every reserved word of every target (gen/emit/reserved.cpp) is an input",
             "// of one keywords_K.clu and an output of the next; tests/gen/test_names.cpp checks that they cover",
             "// the table, tests/targets compiles and runs them in every target. Written by make.py."]
    for j, o in enumerate(outs):
        lines.append(f"?{o} = {ins[j % len(ins)]} + 0.5 * {ins[(j + 1) % len(ins)]};")
    open(f"keywords_{k}.clu", "w").write("\n".join(lines) + "\n")
