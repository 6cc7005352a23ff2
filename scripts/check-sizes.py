#!/usr/bin/env python3
"""Fails when a function or a source file of the layered crates is too long to read.

The rule (ARCHITECTURE.md, "Rules the code keeps"): in `crates/{fe,app,io,cli}/src` no function is
over 150 lines and no file is over 800 lines, except a file that holds one algorithm and says so in
its module docs with a line that starts `//! One algorithm:` (followed by why it stays whole).

A function is counted from its `fn` line to its closing brace, comments and blank lines included;
strings, character literals and comments are skipped when the braces are matched. `--list N` prints
the N longest functions and files instead of checking (exit 0).
"""
import os
import re
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'crates')
CRATES = ('fe', 'app', 'io', 'cli')
MAX_FN = 150
MAX_FILE = 800
EXEMPT = '//! One algorithm:'

FN = re.compile(r'^\s*(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?(extern\s+"C"\s+)?fn\s+(\w+)')


def code_only(text):
    """The text with comments, strings and character literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            i = j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append('\n' * text.count('\n', i, j))
            i = j
        elif c == 'r' and re.match(r'r#*"', text[i:i + 10]) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == '_')):
            m = re.match(r'r(#*)"', text[i:])
            end = '"' + m.group(1)
            j = text.find(end, i + len(m.group(0)))
            j = n if j < 0 else j + len(end)
            out.append('\n' * text.count('\n', i, j))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == '\\' else 1
            j = min(n, j + 1)
            out.append('\n' * text.count('\n', i, j))
            i = j
        elif c == "'":
            m = re.match(r"'(\\.[^']*|[^\\'])'", text[i:])
            if m:
                i += len(m.group(0))
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return ''.join(out)


def functions(path):
    """(name, first line, length in lines) of every function with a body in the file."""
    text = open(path, encoding='utf-8').read()
    code = code_only(text).split('\n')
    found = []
    for k, line in enumerate(code):
        m = FN.match(line)
        if not m:
            continue
        depth, started = 0, False
        for j in range(k, len(code)):
            for ch in code[j]:
                if ch == '{':
                    depth += 1
                    started = True
                elif ch == '}':
                    depth -= 1
                elif ch == ';' and not started and depth == 0:
                    break
            else:
                if started and depth == 0:
                    found.append((m.group(7), k + 1, j - k + 1))
                    break
                continue
            break
    return found


def main():
    listing = int(sys.argv[2]) if len(sys.argv) > 2 and sys.argv[1] == '--list' else 0
    fns, files, bad = [], [], []
    for crate in CRATES:
        src = os.path.join(ROOT, crate, 'src')
        for dp, _, fs in os.walk(src):
            for f in sorted(fs):
                if not f.endswith('.rs'):
                    continue
                p = os.path.join(dp, f)
                rel = os.path.relpath(p, os.path.join(ROOT, '..'))
                text = open(p, encoding='utf-8').read()
                nlines = text.count('\n')
                files.append((nlines, rel))
                if nlines > MAX_FILE and EXEMPT not in text:
                    bad.append('%s: %d lines (at most %d, or a module doc line "%s …")'
                               % (rel, nlines, MAX_FILE, EXEMPT))
                for name, line, length in functions(p):
                    fns.append((length, '%s:%d %s' % (rel, line, name)))
                    if length > MAX_FN:
                        bad.append('%s:%d: fn %s is %d lines (at most %d)' % (rel, line, name, length, MAX_FN))
    if listing:
        for length, where in sorted(fns, reverse=True)[:listing]:
            print('%5d  fn %s' % (length, where))
        for nlines, rel in sorted(files, reverse=True)[:listing]:
            print('%5d  %s' % (nlines, rel))
        return 0
    for b in bad:
        print(b)
    print('check-sizes: ' + ('%d too long' % len(bad) if bad else
          'no function over %d lines, no file over %d lines (but single algorithms)' % (MAX_FN, MAX_FILE)))
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
