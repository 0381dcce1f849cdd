#!/usr/bin/env python3
"""Lists the C++ functions longer than a number of lines, longest first.

Usage: scripts/long_functions.py [LIMIT] [FILE...]  (default: 80, and every .cpp and .hpp that git
knows under src/, include/ and python/src/)

A tokenizer skips comments, string, raw-string and character literals and preprocessor lines;
then a stack of scopes: a `{` at namespace or class scope opens a function body when its
statement holds a `(` before it (brace initialisers, such as `x_{v}` after a constructor's
`) :`, excepted). A function's length runs from the first line of its declaration to its
closing brace; lambdas and local classes count towards the function that holds them. Universal
Ctags (`ctags --fields=+ne`) gives the same list for nbar's sources (2026-11-29).
"""
import re
import sys

KEYWORDS_BEFORE_BODY = {'const', 'noexcept', 'override', 'final', 'mutable', 'try', 'volatile'}

def tokens(text):
    i, n, line = 0, len(text), 1
    at_line_start = True
    while i < n:
        c = text[i]
        if c == '\n':
            line += 1; i += 1; at_line_start = True; continue
        if c in ' \t\r\f\v':
            i += 1; continue
        if at_line_start and c == '#':
            # preprocessor line, with continuations
            while i < n and text[i] != '\n':
                if text[i] == '\\' and i + 1 < n and text[i+1] == '\n':
                    line += 1; i += 2; continue
                i += 1
            continue
        at_line_start = False
        if text.startswith('//', i):
            while i < n and text[i] != '\n': i += 1
            continue
        if text.startswith('/*', i):
            j = text.find('*/', i + 2)
            line += text.count('\n', i, j); i = j + 2; continue
        m = re.match(r'(?:u8|u|U|L)?R"([^()\\ ]{0,16})\(', text[i:i+40])
        if m:
            close = ')' + m.group(1) + '"'
            j = text.find(close, i + m.end())
            line += text.count('\n', i, j); i = j + len(close)
            yield ('str', '""', line); continue
        if c == '"' or (c == "'" and not (i > 0 and text[i-1].isalnum())):  # ' digit separators
            q = c; j = i + 1
            while j < n and text[j] != q:
                if text[j] == '\\': j += 1
                j += 1
            yield ('str', q + q, line); i = j + 1; continue
        m = re.match(r'[A-Za-z_]\w*', text[i:i+200])
        if m:
            yield ('id', m.group(0), line); i += m.end(); continue
        m = re.match(r'[0-9][0-9a-zA-Z_.\']*', text[i:i+100])
        if m:
            yield ('num', m.group(0), line); i += m.end(); continue
        yield ('p', c, line); i += 1

def functions(path):
    text = open(path, encoding='utf-8', errors='replace').read()
    stack = []          # kinds: 'ns', 'class', 'func', 'block', 'init'
    stmt = []           # tokens of the current statement at namespace/class scope
    out = []
    func_start = None
    for kind, tok, line in tokens(text):
        in_func = any(k == 'func' for k in stack)
        if in_func:
            if tok == '{': stack.append('block')
            elif tok == '}':
                k = stack.pop()
                if k == 'func':
                    out.append((func_name, func_start, line))
                    stmt = []
            continue
        if tok == '{':
            words = [t for _, t, _ in stmt]
            prev = words[-1] if words else ''
            if 'namespace' in words or (words[:1] == ['extern'] and len(words) == 2):
                stack.append('ns'); stmt = []; continue
            paren = '(' in words
            first_paren = words.index('(') if paren else len(words)
            if any(w in ('class', 'struct', 'union', 'enum') for w in words[:first_paren]) and not (paren and prev in (')',) ):
                stack.append('class'); stmt = []; continue
            if not paren or '=' in words[:first_paren]:
                stack.append('init'); stmt.append((kind, tok, line)); continue
            # a brace initialiser in a constructor's initialiser list: `name{` after `) :`
            if re.match(r'[A-Za-z_]\w*$', prev) and prev not in KEYWORDS_BEFORE_BODY or prev in ('>',) and ':' in words:
                if ':' in words[first_paren:]:
                    stack.append('init'); stmt.append((kind, tok, line)); continue
            stack.append('func')
            # the name: the identifier before the first top-level '('
            name = words[first_paren - 1] if first_paren > 0 else '?'
            j = first_paren - 2
            while j >= 2 and words[j] == ':' and words[j - 1] == ':':
                name = words[j - 2] + '::' + name; j -= 3
            if name == 'operator' or (first_paren > 1 and words[first_paren - 2] == 'operator'):
                name = 'operator' + (words[first_paren - 1] if name != 'operator' else '')
            func_name = name
            func_start = stmt[0][2] if stmt else line
            continue
        if tok == '}':
            k = stack.pop() if stack else None
            if k == 'init':
                stmt.append((kind, tok, line)); continue
            stmt = []; continue
        if stack and stack[-1] == 'init':
            if tok == '{': stack.append('init')
            stmt.append((kind, tok, line)); continue
        if tok == ';':
            stmt = []; continue
        if tok == ':' and stmt and stmt[-1][1] in ('public', 'private', 'protected'):
            stmt = []; continue
        stmt.append((kind, tok, line))
    return out

def main():
    limit = int(sys.argv[1]) if len(sys.argv) > 1 else 80
    paths = sys.argv[2:]
    if not paths:
        import subprocess
        listed = subprocess.run(['git', 'ls-files', 'src/*.cpp', 'src/*.hpp', 'include/*.hpp', 'python/src/*.cpp',
                                 'python/src/*.hpp'], capture_output=True, text=True, check=True).stdout
        paths = listed.split()
    rows = []
    for p in paths:
        for name, a, b in functions(p):
            n = b - a + 1
            if n > limit: rows.append((n, p, a, name))
    for n, p, a, name in sorted(rows, reverse=True):
        print(f'{n:5d}  {p}:{a}  {name}')

main()
