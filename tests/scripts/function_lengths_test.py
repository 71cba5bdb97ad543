#!/usr/bin/env python3
"""scripts/function_lengths.py on C++ that misleads a naive brace counter:
braces in comments, strings, raw strings and character literals; classes
with inline methods; constructors with brace initialisers; lambdas and
local blocks; data initialisers; operator=. Each function must be found
once, with its first and last line."""

import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..',
                                'scripts'))
import function_lengths  # noqa: E402

SOURCE = r'''#include <string>
#define OPEN {
namespace a {
namespace {
// A comment with a brace {
const int kTable[] = {1, 2, 3};
struct Point {
  int x = 0, y{0};
  int Sum() const { return x + y; }
};
}  // namespace

class Thing : public Base {
 public:
  Thing(int v) : v_{v}, w_(v) {
    const char* s = "}";  /* } */
    char c = '{';
  }
  Thing& operator=(const Thing& other) {
    v_ = other.v_;
    return *this;
  }

 private:
  int v_, w_;
};

int Long(int n) {
  auto f = [&](int k) {
    if (k > 1'000) {
      return k;
    }
    return k + 1;
  };
  std::string raw = R"x(a } b { )x";
  {
    n += f(n);
  }
  return n;
}

}  // namespace a
'''


class FunctionLengthsTest(unittest.TestCase):
    def test_every_function_is_found_once_with_its_lines(self):
        with tempfile.NamedTemporaryFile('w', suffix='.cc',
                                         delete=False) as f:
            f.write(SOURCE)
        try:
            found = function_lengths.functions(f.name)
        finally:
            os.remove(f.name)
        self.assertEqual(found, [
            ('Sum', 9, 9),
            ('Thing', 15, 18),
            ('operator=', 19, 22),
            ('Long', 28, 40),
        ])

    def test_blanking_keeps_lines(self):
        text = 'a /* x\n y */ "s{" // c\nb\n'
        blanked = function_lengths.blank(text)
        self.assertEqual(blanked.count('\n'), text.count('\n'))
        self.assertNotIn('{', blanked)


if __name__ == '__main__':
    unittest.main()
