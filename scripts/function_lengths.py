#!/usr/bin/env python3
"""Lists C++ functions longer than a limit (issue 15: none in master/ or
worker/ beyond about 80 lines).

    scripts/function_lengths.py [--limit N] [--all] PATH...

PATH is a file or a directory (searched for .h and .cc files). A function's
length is its definition's lines, from the first line of its signature to
its closing brace, blank and comment lines included. Exits 1, listing them
longest first, when any function is longer than --limit (default 80); 0
otherwise. --all lists every function found with its length.

A brace counter, not a compiler: comments, string and character literals
(raw strings included) and preprocessor lines are blanked first; then each
'{' outside a function body is classed by the text before it (since the
last ';', '{' or '}'): a namespace, a class, struct, union or enum, an
initialiser ('='), or else, when that text holds a parameter list, a
function. Braces inside a body (blocks, lambdas, local classes) belong to
the body. No macro expansion, so a macro that opens or closes braces would
mislead it; the project has none. On master/ and worker/ it finds the
functions that clang-tidy's readability-function-size finds over a line
threshold (clang-tidy counts the body's lines only, so its counts are a
line or two lower).
"""

import argparse
import os
import re
import sys


def blank(text):
    """`text` with comments, literals and preprocessor lines replaced by
    spaces; newlines are kept, so offsets keep their line numbers."""
    out = list(text)
    i, n = 0, len(text)
    line_start = True

    def wipe(a, b):
        for k in range(a, b):
            if out[k] != '\n':
                out[k] = ' '

    while i < n:
        c = text[i]
        if line_start and c == '#':
            j = i
            while j < n and text[j] != '\n':
                if text[j] == '\\' and j + 1 < n and text[j + 1] == '\n':
                    j += 2
                    continue
                j += 1
            wipe(i, j)
            i = j
            continue
        if c == '\n':
            line_start = True
            i += 1
            continue
        if not c.isspace():
            line_start = False
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            wipe(i, j)
            i = j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            wipe(i, j)
            i = j
        elif c == 'R' and text.startswith('"', i + 1) and (
                i == 0 or not (text[i - 1].isalnum() or text[i - 1] == '_')):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                i += 1
                continue
            end = text.find(')' + m.group(1) + '"', i + m.end())
            j = n if end < 0 else end + len(m.group(1)) + 2
            wipe(i, j)
            i = j
        elif c in '"\'':
            # A digit separator (1'000'000) is no character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and (
                    i + 1 < n and text[i + 1].isalnum()):
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            wipe(i, min(j + 1, n))
            i = j + 1
        else:
            i += 1
    return ''.join(out)


CLASS_HEAD = re.compile(
    r'^(template\s*<.*>\s*)?(\[\[.*\]\]\s*)?(class|struct|union|enum)\b', re.S)
NAMESPACE_HEAD = re.compile(r'^(inline\s+)?(namespace\b|extern\s*$)', re.S)
ACCESS_LABEL = re.compile(r'^\s*(public|private|protected)\s*:(?!:)')


def strip_labels(head):
    head = head.strip()
    while True:
        m = ACCESS_LABEL.match(head)
        if not m:
            return head
        head = head[m.end():].strip()


def after_parameters(head):
    """The text after the parameter list that the first '(' opens."""
    depth = 0
    for k, ch in enumerate(head):
        if ch == '(':
            depth += 1
        elif ch == ')':
            depth -= 1
            if depth == 0:
                return head[k + 1:]
    return ''


def head_kind(head):
    """What a '{' after `head` opens, outside any function body: a
    namespace, a class, a function body, a member's brace initialiser in a
    constructor's initialiser list ('init'), or data."""
    head = strip_labels(head)
    if NAMESPACE_HEAD.match(head):
        return 'namespace'
    if CLASS_HEAD.match(head) and '(' not in head.split(':')[0]:
        return 'class'
    # "operator=" and friends are names, not initialisers.
    unnamed = re.sub(r'operator\s*[^\s(]+', 'operator', head)
    if '(' in unnamed and ')' in unnamed:
        depth, assigned = 0, False
        for ch in unnamed:
            depth += ch in '(<'
            depth -= ch in ')>'
            assigned |= ch == '=' and depth <= 0
        if not assigned:
            initialisers = re.search(r'(?<!:):(?!:)', after_parameters(head))
            if initialisers and re.search(r'[\w>]$', head):
                return 'init'
            return 'function'
    return 'data'


NAME = re.compile(
    r'((?:[\w~]+::)*(?:operator\s*\(\)|operator\s*[^\s\w(]+|'
    r'operator\s+\w+|~?\w+))\s*$')


def function_name(head):
    head = strip_labels(head)
    at = head.find('operator')
    paren = head.find('(', at + len('operator()') if at >= 0 and
                      head.startswith('()', at + 8) else 0)
    m = NAME.search(head[:paren] if paren >= 0 else head)
    return re.sub(r'\s+', '', m.group(1)) if m else '?'


def functions(path):
    """(name, first line, last line) of each function defined in `path`."""
    with open(path, encoding='utf-8') as f:
        text = blank(f.read())
    found = []
    stack = []  # (kind, head start offset, name)
    head_start = 0
    for i, c in enumerate(text):
        in_function = any(kind == 'function' for kind, _, _ in stack)
        if c == '{':
            if in_function:
                stack.append(('block', i, ''))
                continue
            head = text[head_start:i]
            kind = head_kind(head)
            start = head_start + len(head.rstrip()) - len(strip_labels(head))
            stack.append((kind, start,
                          function_name(head) if kind == 'function' else ''))
            if kind != 'init':
                head_start = i + 1
        elif c == '}':
            kind = ''
            if stack:
                kind, start, name = stack.pop()
                if kind == 'function':
                    found.append((name, text.count('\n', 0, start) + 1,
                                  text.count('\n', 0, i) + 1))
            # A member's brace initialiser: the constructor's head goes on.
            if kind != 'init' and not any(
                    k == 'function' for k, _, _ in stack):
                head_start = i + 1
        elif c == ';' and not in_function:
            head_start = i + 1
    return found


def sources(paths):
    for path in paths:
        if os.path.isdir(path):
            for root, _, names in os.walk(path):
                for name in sorted(names):
                    if name.endswith(('.h', '.cc')):
                        yield os.path.join(root, name)
        else:
            yield path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--limit', type=int, default=80)
    parser.add_argument('--all', action='store_true')
    parser.add_argument('paths', nargs='+')
    args = parser.parse_args()
    rows = []
    for path in sorted(sources(args.paths)):
        for name, first, last in functions(path):
            rows.append((last - first + 1, path, first, name))
    rows.sort(key=lambda r: (-r[0], r[1], r[2]))
    over = [r for r in rows if r[0] > args.limit]
    for lines, path, first, name in (rows if args.all else over):
        print(f'{path}:{first}: {name}: {lines} lines')
    if over:
        print(f'{len(over)} functions longer than {args.limit} lines',
              file=sys.stderr)
        return 1
    print(f'function lengths: {len(rows)} functions, none longer than '
          f'{args.limit} lines', file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
