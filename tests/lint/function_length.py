#!/usr/bin/env python3
"""Lint as a test: no function in */src or tools/ is longer than 100 lines.

A function's length is counted from the first line of its declaration
(`template <...>` included) to its closing brace, both included. Lambdas count
towards the function they are written in.

The scan is a small C++ tokenizer and brace matcher, not a compiler: comments,
string and character literals (raw strings included) and preprocessor lines are
removed, then every `{` at namespace or class scope is classified by the
tokens before it as a namespace or class (scanned inside), a function body
(measured), or an initializer (skipped). A file it cannot read as C++ (a brace
or a literal that does not close) is an error, never a pass.

Usage:
  function_length.py SOURCE_DIR            check */src, */*/src and tools/, exit 1 on a function over the limit
  function_length.py --list [--min N] FILE...   print every function of N lines or more

The allow-list below names functions that are known to be too long and are
being rewritten elsewhere; each must still be too long (a stale entry fails
too, so the list shrinks as the debt is paid).
"""
import argparse
import glob
import os
import re
import sys

MAX_LINES = 100

# Known debt, one entry per function: (path relative to the source dir, name).
# Empty: every function is short enough. An entry is for a function being
# rewritten elsewhere; the test fails on an entry whose function is short
# enough, so the list cannot go stale.
ALLOWED: set = set()

SOURCE_SUFFIXES = (".cpp", ".cc", ".hpp", ".h")


class ScanError(Exception):
    pass


# ---- tokenizer ------------------------------------------------------------------

_IDENT = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")
# Numbers with digit separators (1'000) and exponents (1e-3, 0x1p+4).
_NUMBER = re.compile(r"\.?[0-9](?:'?[0-9A-Za-z_.]|[eEpP][+-])*")
_RAW_PREFIX = re.compile(r'(?:u8|u|U|L)?R"([^()\\ \t\n]{0,16})\(')
_STRING_PREFIX = re.compile(r"(?:u8|u|U|L)?(['\"])")
_PUNCT2 = ("::", "->")


class Token:
    __slots__ = ("text", "line")

    def __init__(self, text, line):
        self.text = text
        self.line = line

    def __repr__(self):
        return f"{self.text}@{self.line}"


def tokenize(text, path):
    """Tokens of C++ source with comments, literals and preprocessor lines removed.

    String and character literals become one token '""' so that they still
    separate the tokens around them."""
    tokens = []
    i = 0
    n = len(text)
    line = 1
    at_line_start = True
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
            at_line_start = True
            continue
        if c in " \t\r\f\v":
            i += 1
            continue
        if c == "\\" and i + 1 < n and text[i + 1] == "\n":  # line continuation
            line += 1
            i += 2
            continue
        if c == "#" and at_line_start:  # preprocessor line, with its continuations
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    line += 1
                    i += 1
                elif text.startswith("/*", i):
                    end = text.find("*/", i + 2)
                    if end < 0:
                        raise ScanError(f"{path}:{line}: comment does not close")
                    line += text.count("\n", i, end)
                    i = end + 1
                i += 1
            continue
        at_line_start = False
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    line += 1
                    i += 1
                i += 1
            continue
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            if end < 0:
                raise ScanError(f"{path}:{line}: comment does not close")
            line += text.count("\n", i, end)
            i = end + 2
            continue
        raw = _RAW_PREFIX.match(text, i)
        if raw:
            close = ")" + raw.group(1) + '"'
            end = text.find(close, raw.end())
            if end < 0:
                raise ScanError(f"{path}:{line}: raw string does not close")
            tokens.append(Token('""', line))
            line += text.count("\n", i, end)
            i = end + len(close)
            continue
        literal = _STRING_PREFIX.match(text, i)
        if literal:
            quote = literal.group(1)
            j = literal.end()
            while j < n and text[j] != quote:
                if text[j] == "\n":
                    raise ScanError(f"{path}:{line}: literal does not close on its line")
                j += 2 if text[j] == "\\" else 1
            if j >= n:
                raise ScanError(f"{path}:{line}: literal does not close")
            tokens.append(Token('""', line))
            i = j + 1
            continue
        ident = _IDENT.match(text, i)
        if ident:
            tokens.append(Token(ident.group(0), line))
            i = ident.end()
            continue
        number = _NUMBER.match(text, i)
        if number:
            tokens.append(Token("0", line))
            i = number.end()
            continue
        if text.startswith(_PUNCT2, i):
            tokens.append(Token(text[i : i + 2], line))
            i += 2
            continue
        tokens.append(Token(c, line))
        i += 1
    return tokens


# ---- classifying braces -----------------------------------------------------------

# Tokens that may stand between a function's parameter list and its body.
_TRAILING = {"const", "volatile", "noexcept", "override", "final", "mutable", "constexpr",
             "try", "&", "&&", "throw"}
_CLASS_KEYS = {"class", "struct", "union"}
_ACCESS = {"public", "private", "protected"}
PLACEHOLDER = "{}"  # stands for a skipped braced initializer inside a header


def _skip_template_prefix(header):
    """Index after leading `template <...>` groups, attributes and `typedef`."""
    i = 0
    while i < len(header):
        t = header[i].text
        if t == "template" and i + 1 < len(header) and header[i + 1].text == "<":
            depth = 0
            paren = 0
            j = i + 1
            while j < len(header):
                s = header[j].text
                if s == "(":
                    paren += 1
                elif s == ")":
                    paren -= 1
                elif paren == 0 and s == "<":
                    depth += 1
                elif paren == 0 and s == ">":
                    depth -= 1
                    if depth == 0:
                        break
                j += 1
            i = j + 1
        elif t == "[" and i + 1 < len(header) and header[i + 1].text == "[":
            j = i + 2
            while j + 1 < len(header) and not (header[j].text == "]" and header[j + 1].text == "]"):
                j += 1
            i = j + 2
        elif t in ("typedef", "export", "inline"):
            i += 1
        else:
            return i
    return i


def _top_level(header, start):
    """(index, token text) of the tokens at parenthesis depth 0 from start."""
    depth = 0
    for i in range(start, len(header)):
        t = header[i].text
        if t in "([":
            depth += 1
            if depth == 1:
                yield i, t
            continue
        if t in ")]":
            depth -= 1
            if depth == 0:
                yield i, t
            continue
        if depth == 0:
            yield i, t


def _ends_like_function(header, start):
    """The header, stripped of what may follow a parameter list, ends with `)`,
    or with an initializer list of a constructor."""
    texts = [t.text for t in header[start:]]
    if "(" not in texts:
        return False
    top = list(_top_level(header, start))
    if "operator" not in texts:
        first_paren = next(i for i, t in top if t == "(")
        if any(t == "=" for i, t in top if i < first_paren):
            return False  # a variable's initializer (a lambda, a call)
    # A constructor's initializer list: `) [noexcept] : member(...), member{...}`.
    closes = [k for k, (i, t) in enumerate(top) if t == ")"]
    for k in closes:
        j = k + 1
        while j < len(top) and top[j][1] in _TRAILING:
            j += 1
        if j < len(top) and top[j][1] == ":":
            last = top[-1][1]
            return last in (")", PLACEHOLDER)
    # Strip the tail: qualifiers, noexcept(...), a trailing return type.
    end = len(top)
    arrow = next((k for k, (i, t) in enumerate(top) if t == "->" and k > 0 and top[k - 1][1] == ")"), None)
    if arrow is not None:
        end = arrow
    while end > 0 and top[end - 1][1] in _TRAILING:
        end -= 1
    while end > 0:
        t = top[end - 1][1]
        if t == ")" and end >= 2 and _call_name(header, top, end - 1) in ("noexcept", "throw"):
            end = _open_of(top, end - 1)
            while end > 0 and top[end - 1][1] in _TRAILING:
                end -= 1
            continue
        break
    return end > 0 and top[end - 1][1] == ")"


def _open_of(top, close_k):
    """Position in `top` of the '(' matching the ')' at close_k (they are both depth-0 tokens)."""
    k = close_k - 1
    while k >= 0 and top[k][1] != "(":
        k -= 1
    return k


def _call_name(header, top, close_k):
    k = _open_of(top, close_k)
    return top[k - 1][1] if k > 0 else None


def classify(header):
    """'namespace', 'class', 'function' or 'other' for a `{` after header."""
    if not header:
        return "other"
    texts = [t.text for t in header]
    if "namespace" in texts:
        return "namespace"
    if texts == ["extern", '""']:
        return "namespace"
    start = _skip_template_prefix(header)
    if start < len(header):
        first = header[start].text
        if first in _CLASS_KEYS:
            return "class"
        if first == "enum":
            return "other"
    if _ends_like_function(header, start):
        return "function"
    return "other"


def function_name(header):
    """The declarator's name, qualified as written: `Foo::bar`, `run`, `operator()`."""
    start = _skip_template_prefix(header)
    top = list(_top_level(header, start))
    texts = [t.text for t in header]
    if "operator" in texts:
        k = texts.index("operator")
        name = [texts[k]]
        j = k + 1
        # operator() : the name's own parentheses; otherwise the symbol(s) up to '('.
        if j < len(texts) and texts[j] == "(" and j + 1 < len(texts) and texts[j + 1] == ")":
            name.append("()")
        else:
            while j < len(texts) and texts[j] != "(":
                name.append(texts[j])
                j += 1
        while k >= 2 and texts[k - 1] == "::" and _IDENT.fullmatch(texts[k - 2]):
            name[:0] = [texts[k - 2], "::"]
            k -= 2
        return "".join(name)
    first_paren = next((i for i, t in top if t == "("), None)
    if first_paren is None or first_paren == 0:
        return "?"
    k = first_paren - 1
    parts = [texts[k]]
    if texts[k] in (">",):
        return "?"
    if k >= 1 and texts[k - 1] == "~":
        parts.insert(0, "~")
        k -= 1
    while k >= 2 and texts[k - 1] == "::":
        parts[:0] = [texts[k - 2], "::"]
        k -= 2
    return "".join(parts)


def match_brace(tokens, i, path):
    depth = 0
    for j in range(i, len(tokens)):
        t = tokens[j].text
        if t == "{":
            depth += 1
        elif t == "}":
            depth -= 1
            if depth == 0:
                return j
    raise ScanError(f"{path}:{tokens[i].line}: '{{' does not close")


def functions_in(path, text=None):
    """(name, first line, last line, line of the body's `{`) of every function
    body at namespace or class scope."""
    if text is None:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    tokens = tokenize(text, path)
    found = []
    header = []
    open_scopes = []  # lines of the namespaces and classes we are inside
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        t = tok.text
        if t == ";":
            header = []
        elif t == ":" and header and header[-1].text in _ACCESS and len(header) == 1:
            header = []
        elif t == "}":
            if not open_scopes:
                raise ScanError(f"{path}:{tok.line}: '}}' closes nothing")
            open_scopes.pop()
            header = []
        elif t == "{":
            kind = classify(header)
            if kind in ("namespace", "class"):
                open_scopes.append(tok.line)
                header = []
            else:
                end = match_brace(tokens, i, path)
                if kind == "function":
                    found.append((function_name(header), header[0].line, tokens[end].line,
                                  tok.line))
                    header = []
                else:
                    header.append(Token(PLACEHOLDER, tok.line))
                i = end
        else:
            header.append(tok)
        i += 1
    if open_scopes:
        raise ScanError(f"{path}:{open_scopes[-1]}: '{{' does not close")
    return found


# ---- the check ----------------------------------------------------------------------

# Where the checked code is: every part's src/ (physics has two parts, model/
# and server/, each with its src/), and tools/ (the demo team, the report, the
# small programs), which are programs like the others.
SOURCE_GLOBS = (os.path.join("*", "src"), os.path.join("*", "*", "src"), "tools")


def source_files(source_dir):
    files = []
    folders = set()
    for pattern in SOURCE_GLOBS:
        folders.update(glob.glob(os.path.join(source_dir, pattern)))
    for folder in sorted(folders):
        for root, _, names in os.walk(folder):
            for name in sorted(names):
                if name.endswith(SOURCE_SUFFIXES):
                    files.append(os.path.join(root, name))
    return sorted(set(files))


def check(source_dir):
    files = source_files(source_dir)
    if not files:
        print(f"function_length: no source files under {source_dir}/*/src or tools",
              file=sys.stderr)
        return 1
    too_long = []
    allowed_seen = set()
    count = 0
    unreadable = []
    for path in files:
        rel = os.path.relpath(path, source_dir).replace(os.sep, "/")
        try:
            functions = functions_in(path)
        except (ScanError, OSError, UnicodeDecodeError) as error:
            unreadable.append(f"cannot scan {error}")
            continue
        for name, first, last, _ in functions:
            count += 1
            lines = last - first + 1
            if lines <= MAX_LINES:
                continue
            if (rel, name) in ALLOWED:
                allowed_seen.add((rel, name))
                print(f"allowed: {rel}:{first}: {name} is {lines} lines (known debt)")
                continue
            too_long.append(f"{rel}:{first}: {name} is {lines} lines (at most {MAX_LINES})")
    stale = sorted(ALLOWED - allowed_seen)
    for line in too_long:
        print(f"too long: {line}")
    for line in unreadable:
        print(line)
    for rel, name in stale:
        print(f"stale allow-list entry: {rel}: {name} is not over {MAX_LINES} lines (or is gone): "
              "remove it from tests/lint/function_length.py")
    print(f"function_length: {len(too_long)} of {count} functions in {len(files)} files over "
          f"{MAX_LINES} lines, {len(allowed_seen)} allowed, {len(stale)} stale allow-list entries, "
          f"{len(unreadable)} files not scanned")
    return 1 if too_long or stale or unreadable else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--list", action="store_true", help="list the functions of the given files")
    parser.add_argument("--min", type=int, default=0, help="with --list: only functions this long")
    parser.add_argument("paths", nargs="+")
    args = parser.parse_args()
    try:
        if args.list:
            for path in args.paths:
                for name, first, last, body in functions_in(path):
                    if last - first + 1 >= args.min:
                        print(f"{path}:{first}-{last}: {name} ({last - first + 1} lines, "
                              f"body from line {body})")
            return 0
        if len(args.paths) != 1:
            parser.error("give one SOURCE_DIR (or --list FILE...)")
        return check(args.paths[0])
    except ScanError as error:
        print(f"function_length: cannot scan {error}", file=sys.stderr)
        return 1
    except OSError as error:
        print(f"function_length: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
