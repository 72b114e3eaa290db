#!/usr/bin/env python3
"""Breaks a written scene.vt.obj on purpose, for the checkers' negative tests (run.sh negative).

  corrupt.py shift-vt IN.obj OUT.obj ATLAS_WIDTH   the vt line that the most face corners use
                                                   (an interior one), its u moved by one texel
  corrupt.py drop-face IN.obj OUT.obj              the middle face line left out

Prints what it changed. Only absolute (positive) face indices are counted for shift-vt.
"""

import sys


def main():
    mode, src, dst = sys.argv[1:4]
    with open(src, "rb") as f:
        lines = f.read().split(b"\n")
    if mode == "shift-vt":
        width = int(sys.argv[4])
        vt_lines, uses = [], {}
        for n, line in enumerate(lines):
            toks = line.split()
            if toks[:1] == [b"vt"]:
                vt_lines.append(n)
            elif toks[:1] == [b"f"]:
                for c in toks[1:]:
                    parts = c.split(b"/")
                    if len(parts) > 1 and parts[1] and not parts[1].startswith(b"-"):
                        uses[int(parts[1])] = uses.get(int(parts[1]), 0) + 1
        best = max(sorted(uses), key=lambda i: uses[i])
        n = vt_lines[best - 1]
        toks = lines[n].split()
        u = float(toks[1]) + 1.0 / width
        lines[n] = b" ".join([toks[0], repr(u).encode()] + toks[2:])
        print("corrupt.py: vt %d (line %d, used by %d corners): u %s -> %r"
              % (best, n + 1, uses[best], toks[1].decode(), u))
    elif mode == "drop-face":
        faces = [n for n, line in enumerate(lines) if line.split()[:1] == [b"f"]]
        n = faces[len(faces) // 2]
        print("corrupt.py: dropped line %d: %s" % (n + 1, lines[n].decode()))
        del lines[n]
    else:
        print("corrupt.py: unknown mode '%s'" % mode, file=sys.stderr)
        return 2
    with open(dst, "wb") as f:
        f.write(b"\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
