#!/usr/bin/env python3
"""The scanner behind test_function_length (function_length.py) on C++ that
could fool a brace matcher: braces in literals and comments, constructors'
initializer lists, brace initializers, operators, templates, lambdas, classes
and namespaces. And that the check fails on a function over the limit, on a
stale allow-list entry and on a file it cannot read."""
import contextlib
import io
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import function_length as fl  # noqa: E402


def scan(text):
    return [(name, first, last) for name, first, last, _ in fl.functions_in("t.cpp", text)]


class Scanner(unittest.TestCase):
    def test_free_functions_and_their_lines(self):
        text = "int f(int x) {\n  return x;\n}\n\nvoid g()\n{\n}\n"
        self.assertEqual(scan(text), [("f", 1, 3), ("g", 5, 7)])

    def test_braces_in_literals_comments_and_preprocessor_lines_do_not_count(self):
        text = (
            "#define OPEN {\n"
            "#define MANY(x) \\\n  { x }\n"
            "// } a comment {\n"
            "/* { */ int f() {\n"
            "  const char* s = \"}{\\\"}\";\n"
            "  char c = '{';\n"
            "  auto raw = R\"x(}})\" {)x\";\n"
            "  int n = 1'000'000;  // digit separators are no character literals\n"
            "  char d = '}';\n"
            "  return 0;\n"
            "}\n"
            "void g() {}\n"
        )
        self.assertEqual(scan(text), [("f", 5, 12), ("g", 13, 13)])

    def test_constructor_initializer_lists_with_parentheses_and_braces(self):
        text = (
            "Foo::Foo(int a)\n"
            "    : a_(a), b_{a, 2}, c_{} {\n"
            "  run();\n"
            "}\n"
            "Bar::Bar() : x_(1) {}\n"
            "Baz::Baz() noexcept : v_{1} { go(); }\n"
        )
        self.assertEqual(scan(text), [("Foo::Foo", 1, 4), ("Bar::Bar", 5, 5), ("Baz::Baz", 6, 6)])

    def test_qualifiers_trailing_return_types_operators_and_destructors(self):
        text = (
            "int A::get() const noexcept { return 1; }\n"
            "auto h(int x) -> std::vector<int> { return {x}; }\n"
            "bool operator==(const A& a, const A& b) { return a.v == b.v; }\n"
            "int A::operator()(int x) const { return x; }\n"
            "A::~A() { stop(); }\n"
            "void k() noexcept(true) {}\n"
        )
        self.assertEqual([n for n, _, _ in scan(text)],
                         ["A::get", "h", "operator==", "A::operator()", "A::~A", "k"])

    def test_initializers_are_no_functions(self):
        text = (
            "const std::map<int, int> kTable = {\n  {1, 2},\n  {3, 4},\n};\n"
            "Point origin{0, 0};\n"
            "auto lambda = [](int x) {\n  return x;\n};\n"
            "enum class Phase { Start, Over };\n"
            "int after() { return 0; }\n"
        )
        self.assertEqual(scan(text), [("after", 10, 10)])

    def test_lambdas_count_towards_their_function(self):
        text = "void f() {\n  auto g = [&](int x) {\n    return x;\n  };\n  g(1);\n}\n"
        self.assertEqual(scan(text), [("f", 1, 6)])

    def test_functions_inside_namespaces_classes_and_templates(self):
        text = (
            "namespace a::b {\n"
            "namespace {\n"
            "struct S : Base<int> {\n"
            "  S() = default;\n"
            "  int v() const { return 1; }\n"
            " public:\n"
            "  void w() {}\n"
            "  struct Inner { void x() {} };\n"
            "};\n"
            "}  // namespace\n"
            "template <typename T, class U = int>\n"
            "T twice(T t) {\n"
            "  return t + t;\n"
            "}\n"
            "extern \"C\" {\n"
            "void c_api() {}\n"
            "}\n"
            "}  // namespace a::b\n"
        )
        self.assertEqual(scan(text), [("v", 5, 5), ("w", 7, 7), ("x", 8, 8), ("twice", 11, 14),
                                      ("c_api", 16, 16)])

    def test_unbalanced_braces_and_open_literals_are_errors(self):
        for text in ("void f() {\n", "}\n", "void f() { const char* s = \"open; }\n",
                     "/* open comment\n"):
            with self.assertRaises(fl.ScanError, msg=text):
                fl.functions_in("t.cpp", text)


class Check(unittest.TestCase):
    def run_check(self, files, allowed=frozenset()):
        with tempfile.TemporaryDirectory(dir=os.environ.get("TMPDIR")) as root:
            for path, text in files.items():
                os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
                with open(os.path.join(root, path), "w") as f:
                    f.write(text)
            saved = fl.ALLOWED
            fl.ALLOWED = set(allowed)
            out = io.StringIO()
            try:
                with contextlib.redirect_stdout(out):
                    status = fl.check(root)
            finally:
                fl.ALLOWED = saved
            return status, out.getvalue()

    @staticmethod
    def function(name, lines):
        """A function of exactly `lines` lines."""
        return f"void {name}() {{\n" + "  step();\n" * (lines - 2) + "}\n"

    def test_a_function_over_the_limit_fails_and_is_named(self):
        status, out = self.run_check({"x/src/a.cpp": self.function("long_one", 101)})
        self.assertEqual(status, 1)
        self.assertIn("x/src/a.cpp:1: long_one is 101 lines", out)

    def test_at_the_limit_passes(self):
        status, out = self.run_check({"x/src/a.cpp": self.function("just_so", 100)})
        self.assertEqual(status, 0, out)

    def test_an_allowed_function_passes_and_a_stale_entry_fails(self):
        files = {"x/src/a.cpp": self.function("debt", 150)}
        status, out = self.run_check(files, {("x/src/a.cpp", "debt")})
        self.assertEqual(status, 0, out)
        status, out = self.run_check({"x/src/a.cpp": self.function("debt", 20)},
                                     {("x/src/a.cpp", "debt")})
        self.assertEqual(status, 1)
        self.assertIn("stale allow-list entry: x/src/a.cpp: debt", out)

    def test_only_src_folders_are_checked(self):
        status, out = self.run_check({"x/src/a.cpp": self.function("short", 10),
                                      "tests/t.cpp": self.function("long_test", 300)})
        self.assertEqual(status, 0, out)

    def test_a_file_that_cannot_be_scanned_fails(self):
        status, _ = self.run_check({"x/src/a.cpp": "void f() {\n"})
        self.assertEqual(status, 1)


if __name__ == "__main__":
    unittest.main()
