#!/usr/bin/env python3
"""Lists the rates and tip radii of the library's messages that are not typed.

A rate ("omega", "omega_k", "omega_min" ... then "=", " = " or " " and a printf conversion) or a
tip radius ("tip radius" and a conversion) in a string literal of a library source file
(src/*/*.c outside src/cli/) must carry its mark (WHIRL_Q_RATE, WHIRL_Q_LENGTH, src/core/error.h)
so that the program prints it in the user's units, unless the line holding the literal, or the
line above it, says /* dimensionless: the file's text */ (a message that quotes a dimensionless file's numbers as
written, or a format that reads them). Prints each unmarked one as FILE:LINE: TEXT
and exits 1 if there is any. --apply inserts the marks (then reflow the lines by hand).
Usage: message_quantities.py [--apply] [ROOT]"""
import glob
import os
import re
import sys

CONV = r'%[-+ #0]*[0-9]*(?:\.[0-9*]+)?(?:l|ll|z|h)?[a-zA-Z]'
QUANTITY = re.compile(r'(?<![A-Za-z0-9_%])(omega(?:_(?:%z?l?[dui]|[A-Za-z0-9])*)?|tip radius)'
                      r'( = |=| )(' + CONV + ')')
LITERAL = re.compile(r'"(?:[^"\\\n]|\\.)*"')
# adjacent literals, which C joins: a quantity may straddle two of them
SEQUENCE = re.compile(r'"(?:[^"\\\n]|\\.)*"(?:\s*"(?:[^"\\\n]|\\.)*")+')
# files whose literals with rates are not messages (headers of output files)
# the mark of a literal that quotes or reads a dimensionless file's numbers as written
FILE_TEXT = "/* dimensionless: the file's text */"
NOT_MESSAGES = {'src/studies/scene_run.c', 'src/studies/atlas_text.c'}


def mark(m):
    kind = 'WHIRL_Q_LENGTH' if m.group(1) == 'tip radius' else 'WHIRL_Q_RATE'
    return m.group(1) + m.group(2) + '" ' + kind + ' "' + m.group(3)


def main(argv):
    apply = '--apply' in argv
    args = [a for a in argv if a != '--apply']
    root = args[0] if args else '.'
    found = 0
    for path in sorted(glob.glob(os.path.join(root, 'src/*/*.c'))):
        rel = os.path.relpath(path, root)
        if rel.startswith('src/cli/') or rel in NOT_MESSAGES:
            continue
        src = open(path).read()
        out, pos = [], 0
        lines = src.split('\n')
        for lit in LITERAL.finditer(src):
            line = src.count('\n', 0, lit.start()) + 1
            if FILE_TEXT in lines[line - 1] or (line > 1 and FILE_TEXT in lines[line - 2]):
                continue
            for q in QUANTITY.finditer(lit.group(0)):
                print('%s:%d: %s' % (rel, line, q.group(0)))
                found += 1
            out += [src[pos:lit.start()], QUANTITY.sub(mark, lit.group(0))]
            pos = lit.end()
        out.append(src[pos:])
        for seq in SEQUENCE.finditer(src):
            joined = ''.join(LITERAL.findall(seq.group(0))).replace('""', '')
            singles = sum(len(QUANTITY.findall(lit)) for lit in LITERAL.findall(seq.group(0)))
            across = QUANTITY.findall(joined.replace('"', ''))
            if len(across) > singles:
                line = src.count('\n', 0, seq.start()) + 1
                print('%s:%d: a quantity across two literals (mark it by hand)' % (rel, line))
                found += len(across) - singles
        if apply:
            open(path, 'w').write(''.join(out))
    return 1 if found and not apply else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
