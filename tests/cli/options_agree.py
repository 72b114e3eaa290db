#!/usr/bin/env python3
"""For every tool: the long options it really accepts agree with those its --help lists, its man
page lists and its docs/cli page lists.

  options_agree.py SOURCE_DIR TOOLS_DIR MAN_DIR

Accepted: the getopt_long tables of the tool's sources (tools/vt-x.c or tools/vt-x/*.c), each
entry confirmed by running the tool with it (never "unknown option"); a made-up option must be
refused, which shows the probe can tell. Listed in --help and the man page: the options that
start an option line (indented at most 8 columns, possibly after "-x, ", or after "; " on the
same line), not those named in descriptions. Listed in the docs: the options in the first column
of the page's tables. Prints one "ok" line per tool, or every difference, and exits 1 on any.
A self-test first shows that a help with one option left out is reported."""
import os
import re
import subprocess
import sys

TOOLS = ["vt-atlas", "vt-offset", "vt-tiles", "vt-info", "vt-convert", "vt-merge", "vt-export",
         "vt-view", "vt-obj2ply", "vt-wang"]
ENTRY = re.compile(r'\{\s*"([a-z0-9][a-z0-9-]*)"\s*,\s*(?:no|required|optional)_argument')
HELP_OPT = re.compile(r"(?:^[ \t]{0,8}|;\s+)(?:-[A-Za-z0-9], )?--([a-z0-9][a-z0-9-]*)")
DOC_ROW = re.compile(r"^\|([^|]*)\|")
DOC_OPT = re.compile(r"--([a-z0-9][a-z0-9-]*)")
UNKNOWN = re.compile(r"unknown option|unrecognized option|invalid option")


def source_options(src, tool):
    folder = os.path.join(src, "tools", tool)
    files = [os.path.join(folder, f) for f in sorted(os.listdir(folder)) if f.endswith(".c")] \
        if os.path.isdir(folder) else [os.path.join(src, "tools", tool + ".c")]
    found = set()
    for f in files:
        text = open(f).read()
        for table in re.finditer(r"struct option\s+\w+\s*\[\s*\]\s*=\s*\{(.*?)\};", text, re.S):
            found |= set(ENTRY.findall(table.group(1)))
    return found


def help_options(text):
    found = set()
    for line in text.splitlines():
        found |= set(HELP_OPT.findall(line))
    return found


def man_options(path):
    text = open(path).read()
    body = text.split("\n.nf\n", 1)[1].split("\n.fi\n", 1)[0]
    body = body.replace("\\&", "").replace("\\e", "\\")
    return help_options(body)


def doc_options(path):
    found = set()
    for line in open(path):
        m = DOC_ROW.match(line)
        if m and m.group(1).strip().startswith("`-"):
            found |= set(DOC_OPT.findall(m.group(1)))
    return found


def probe(exe, option):
    """True when the tool does not call the option unknown."""
    env = dict(os.environ, DISPLAY="", WAYLAND_DISPLAY="")
    try:
        r = subprocess.run([exe, "--" + option], stdin=subprocess.DEVNULL,
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env,
                           timeout=30)
    except subprocess.TimeoutExpired:
        return True
    return not UNKNOWN.search(r.stderr.decode(errors="replace"))


def differences(tool, accepted, lists):
    out = []
    for what, names in lists.items():
        if names is None:
            out.append(f"{tool}: no {what}")
            continue
        for n in sorted(accepted - names):
            out.append(f"{tool}: --{n} is accepted but not in the {what}")
        for n in sorted(names - accepted):
            out.append(f"{tool}: --{n} is in the {what} but not accepted")
    return out


def main():
    src, tools_dir, man_dir = sys.argv[1:4]
    # Self-test: a help that leaves one option out is reported.
    fake = "  -o, --output FILE  out\n      --mode M     m\n  -h, --help   help;  --version  v\n"
    assert help_options(fake) == {"output", "mode", "help", "version"}, help_options(fake)
    assert differences("t", {"output", "mode", "help", "version", "layer"},
                       {"help": help_options(fake)}), "a missing option was not reported"
    problems = []
    for tool in TOOLS:
        exe = os.path.join(tools_dir, tool)
        accepted = source_options(src, tool)
        if not accepted:
            problems.append(f"{tool}: no getopt_long table found in its sources")
            continue
        for n in sorted(accepted):
            if n not in ("help", "version") and not probe(exe, n):
                problems.append(f"{tool}: --{n} is in its table but the tool calls it unknown")
        if probe(exe, "no-such-option-x"):
            problems.append(f"{tool}: the probe cannot tell an unknown option")
        helptext = subprocess.run([exe, "--help"], capture_output=True, text=True).stdout
        man = os.path.join(man_dir, tool + ".1")
        doc = os.path.join(src, "docs", "cli", tool + ".md")
        lists = {"--help": help_options(helptext),
                 "man page": man_options(man) if os.path.exists(man) else None,
                 "docs/cli page": doc_options(doc) if os.path.exists(doc) else None}
        found = differences(tool, accepted, lists)
        problems += found
        if not found:
            print(f"ok {tool}: {len(accepted)} long options, the same in --help, the man page "
                  f"and docs/cli/{tool}.md")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
