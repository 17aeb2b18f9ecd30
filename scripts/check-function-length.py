#!/usr/bin/env python3
"""Lists every C++ function definition longer than a line limit (120 by default).

A function's length counts the lines from the start of its signature to its closing brace, both
included; lambdas and local classes inside it count toward it, a class or namespace body does
not. Braces are matched on a token stream that skips comments, string and character literals
(raw strings included) and preprocessor lines, which is enough for this codebase's style.

Usage: check-function-length.py [--root DIR] [--max N] [--skip DIR ...] [FOLDER ...]
FOLDERs (default: src baselines) are searched for *.cc and *.h; --skip drops folders below them.
Prints `path:line: name N lines` for each long function and exits 1 if there is any.
"""

import argparse
import pathlib
import re
import sys

# A token: (text, line). Strings and characters become the single token '""'.
_IDENT = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")
_NUMBER = re.compile(r"\.?[0-9](?:[0-9A-Za-z_.]|'(?=[0-9A-Za-z])|[eEpP][+-])*")
_RAW_PREFIX = re.compile(r"(?:u8|u|U|L)?R\"([^()\\ ]{0,16})\(")
_PUNCT3 = ("<<=", ">>=", "->*", "...", "<=>")
_PUNCT2 = ("::", "->", "++", "--", "<<", ">>", "<=", ">=", "==", "!=", "&&", "||",
           "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", ".*")


def Tokenize(text):
  """Returns the list of (token, line) of C++ source `text`, without comments and literals."""
  tokens = []
  i, line, n = 0, 1, len(text)
  at_line_start = True
  while i < n:
    c = text[i]
    # Whitespace and line breaks.
    if c == "\n":
      line += 1
      i += 1
      at_line_start = True
      continue
    if c in " \t\r\f\v":
      i += 1
      continue
    # Preprocessor lines (with backslash continuations) carry no braces of interest.
    if c == "#" and at_line_start:
      while i < n and text[i] != "\n":
        if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
          line += 1
          i += 1
        i += 1
      continue
    at_line_start = False
    # Comments.
    if text.startswith("//", i):
      while i < n and text[i] != "\n":
        i += 1
      continue
    if text.startswith("/*", i):
      end = text.find("*/", i + 2)
      end = n if end < 0 else end + 2
      line += text.count("\n", i, end)
      i = end
      continue
    # Raw strings R"delim( ... )delim", with an optional encoding prefix.
    raw = _RAW_PREFIX.match(text, i)
    if raw:
      close = ")" + raw.group(1) + '"'
      end = text.find(close, raw.end())
      end = n if end < 0 else end + len(close)
      tokens.append(('""', line))
      line += text.count("\n", i, end)
      i = end
      continue
    # String and character literals (an encoding prefix is lexed as an identifier before them).
    if c in "\"'":
      j = i + 1
      while j < n and text[j] != c and text[j] != "\n":
        j += 2 if text[j] == "\\" else 1
      tokens.append(('""', line))
      i = j + 1
      continue
    # Identifiers, numbers (with digit separators), punctuation.
    m = _IDENT.match(text, i) or _NUMBER.match(text, i)
    if m:
      tokens.append((m.group(0), line))
      i = m.end()
      continue
    for p in _PUNCT3 + _PUNCT2:
      if text.startswith(p, i):
        tokens.append((p, line))
        i += len(p)
        break
    else:
      tokens.append((c, line))
      i += 1
  return tokens


_NOT_A_NAME = {"decltype", "noexcept", "alignas", "sizeof", "requires", "void", "int", "bool",
               "double", "float", "char", "auto", "const", "__attribute__", "return"}


def _FunctionName(head):
  """The (possibly qualified) name before the parameter list of a function head."""
  for k, (tok, _) in enumerate(head):
    if tok != "(" or k == 0:
      continue
    prev = head[k - 1][0]
    if prev in _NOT_A_NAME:
      continue
    if _IDENT.fullmatch(prev) or prev in ("]", ")") or not prev[0].isalnum():
      # Walk back over `A::B::~C`, `operator()`, `operator==`.
      j = k - 1
      if prev == ")" and j >= 2 and head[j - 1][0] == "(" and head[j - 2][0] == "operator":
        j -= 2
      elif j >= 1 and head[j - 1][0] == "operator":
        j -= 1
      while j >= 2 and head[j - 1][0] in ("::", "~") and (
          head[j - 1][0] == "~" or _IDENT.fullmatch(head[j - 2][0]) or head[j - 2][0] == ">"):
        if head[j - 1][0] == "~":
          j -= 1
          continue
        j -= 2
        if head[j][0] == ">":  # Class template qualifier: skip back to its '<'.
          depth = 0
          while j > 0:
            depth += {">": 1, ">>": 2, "<": -1}.get(head[j][0], 0)
            if depth <= 0:
              break
            j -= 1
          j -= 1
      if j > 0 and head[j - 1][0] == "~":
        j -= 1
      return "".join(t for t, _ in head[j:k])
  return "?"


def _DepthZero(head):
  """Yields (index, token) of `head` outside parentheses, brackets and `template <...>` lists."""
  depth = 0
  angle = 0  # Depth inside a `template <...>` parameter list.
  for k, (tok, _) in enumerate(head):
    if angle:
      angle += {"<": 1, ">": -1, ">>": -2}.get(tok, 0)
      continue
    if tok == "<" and k > 0 and head[k - 1][0] == "template":
      angle = 1
      continue
    if tok in ("(", "["):
      depth += 1
    elif tok in (")", "]"):
      depth -= 1
    elif depth == 0:
      yield k, tok


def _IsInitializerListBrace(head):
  """True when `{` opens a member initializer `x_{...}` in a constructor's initializer list."""
  if len(head) < 2 or not (_IDENT.fullmatch(head[-1][0]) or head[-1][0] == ">"):
    return False
  saw_close_paren = False
  for k, tok in _DepthZero(head):
    if tok == ":" and k > 0 and head[k - 1][0] == ")":
      saw_close_paren = True
  return saw_close_paren and head[-1][0] not in ("const", "override", "final", "noexcept")


def _Classify(head):
  """What a `{` at namespace or class scope opens: namespace, class, init, member_init, function."""
  zero = list(_DepthZero(head))
  words = [tok for _, tok in zero if tok != "template"]
  if not words:
    return "block"
  if "namespace" in words:
    return "namespace"
  if words[0] == "extern" and len(words) <= 2:
    return "namespace"  # extern "C" { ... }
  if words[0] in ("class", "struct", "union"):
    return "class"
  if words[0] == "enum":
    return "init"
  # An initializer (`T x = {...}`, not `operator=`), or an aggregate after a comma.
  if any(tok == "=" and (k == 0 or head[k - 1][0] != "operator") for k, tok in zero) or \
      words[-1] in (",", "return"):
    return "init"
  if _IsInitializerListBrace(head):
    return "member_init"
  if any(tok == "(" for tok, _ in head):
    return "function"
  return "init"  # e.g. a brace-initialised variable `T x{...}`


_LAMBDA_TAIL = {"mutable", "constexpr", "consteval", "noexcept", "->", "::", "<", ">", "*", "&", "&&", ","}


def _LambdaStart(head):
  """Index of the `[` opening a lambda whose body the next `{` opens, or None."""
  k = len(head) - 1
  # Back over a trailing return type and specifiers to the parameter list or capture.
  while k >= 0 and (head[k][0] in _LAMBDA_TAIL or _IDENT.fullmatch(head[k][0])):
    k -= 1
  if k >= 0 and head[k][0] == ")":
    depth = 0
    while k >= 0:
      depth += {")": 1, "(": -1}.get(head[k][0], 0)
      if depth == 0:
        break
      k -= 1
    k -= 1
  if k < 0 or head[k][0] != "]":
    return None
  depth = 0
  while k >= 0:
    depth += {"]": 1, "[": -1}.get(head[k][0], 0)
    if depth == 0:
      break
    k -= 1
  if k <= 0 or head[k - 1][0] not in ("(", ",", "=", "{}", "return"):
    return None
  return k


def _ParenDepth(head):
  """How many parentheses or brackets of `head` are still open."""
  depth = 0
  for tok, _ in head:
    if tok in ("(", "["):
      depth += 1
    elif tok in (")", "]"):
      depth -= 1
  return depth


def _SkipBraces(tokens, i):
  """Index just past the `}` that matches the `{` at tokens[i]."""
  depth = 0
  while i < len(tokens):
    tok = tokens[i][0]
    if tok == "{":
      depth += 1
    elif tok == "}":
      depth -= 1
      if depth == 0:
        return i + 1
    i += 1
  return i


def FindFunctions(tokens):
  """Returns (name, first line, last line) of every function defined at namespace/class scope."""
  found = []

  def Scope(i):
    head = []
    while i < len(tokens):
      tok, _ = tokens[i]
      if tok == ";":
        head = []
        i += 1
      elif tok == "}":
        return i + 1
      elif tok == ":" and len(head) == 1 and head[0][0] in ("public", "private", "protected"):
        head = []
        i += 1
      elif tok == "{" and _LambdaStart(head) is not None:
        # A lambda at namespace or class scope (e.g. a registration's body): a function too.
        start = _LambdaStart(head)
        end = _SkipBraces(tokens, i)
        name = _FunctionName(head[:start] + [("(", 0)]) if start > 0 else "?"
        found.append((f"{name} lambda", head[start][1], tokens[end - 1][1]))
        head = head + [("{}", tokens[i][1])]
        i = end
      elif tok == "{" and _ParenDepth(head) > 0:
        # A braced default argument or initializer inside a parameter list.
        end = _SkipBraces(tokens, i)
        head = head + [("{}", tokens[i][1])]
        i = end
      elif tok == "{":
        kind = _Classify(head)
        if kind in ("namespace", "class"):
          i = Scope(i + 1)
          head = []
        elif kind == "member_init":
          end = _SkipBraces(tokens, i)
          head = head + [("{}", tokens[i][1])]
          i = end
        elif kind == "function":
          end = _SkipBraces(tokens, i)
          found.append((_FunctionName(head), head[0][1], tokens[end - 1][1]))
          head = []
          i = end
        else:
          end = _SkipBraces(tokens, i)
          head = head + [("{}", tokens[i][1])]
          i = end
      else:
        head.append(tokens[i])
        i += 1
    return i

  i = 0
  while i < len(tokens):
    i = Scope(i)
  return found


def main(argv):
  parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
  parser.add_argument("folders", nargs="*", default=["src", "baselines"])
  parser.add_argument("--root", default=str(pathlib.Path(__file__).resolve().parent.parent),
                      help="repository root the folders are relative to")
  parser.add_argument("--max", type=int, default=120, help="longest allowed function, in lines")
  parser.add_argument("--skip", nargs="*", default=[], help="folders (relative to root) to leave out")
  args = parser.parse_args(argv)

  root = pathlib.Path(args.root)
  skips = [pathlib.PurePosixPath(s.rstrip("/")) for s in args.skip]
  files = []
  for folder in args.folders:
    base = root / folder
    if base.is_file():
      files.append(base)
      continue
    if not base.is_dir():
      print(f"check-function-length: no folder {base}", file=sys.stderr)
      return 2
    files += [p for p in base.rglob("*") if p.suffix in (".cc", ".h") and p.is_file()]

  failures = 0
  for path in sorted(set(files)):
    rel = pathlib.PurePosixPath(path.relative_to(root).as_posix()) if path.is_relative_to(root) \
        else pathlib.PurePosixPath(path.as_posix())
    if any(rel.is_relative_to(s) for s in skips):
      continue
    text = path.read_text(encoding="utf-8", errors="replace")
    for name, first, last in FindFunctions(Tokenize(text)):
      length = last - first + 1
      if length > args.max:
        print(f"{rel}:{first}: {name} {length} lines")
        failures += 1
  return 1 if failures else 0


if __name__ == "__main__":
  sys.exit(main(sys.argv[1:]))
