#!/bin/sh
# Every public header that says it throws aief::Error declares it: a user's
# `catch (const aief::Error&)` compiles with that header alone.
# Usage: public_headers_declare_their_errors.sh CXX INCLUDE_DIR...
compiler=$1
shift
flags=""
for dir in "$@"; do flags="$flags -I$dir"; done
status=0
for header in "$1"/aief/*.hpp; do
  grep -q 'aief::Error' "$header" || continue
  printf '#include "%s"\nvoid caught() {\n  try {\n  } catch (const aief::Error&) {\n  }\n}\n' "$header" |
    $compiler -std=c++17 -fsyntax-only $flags -x c++ - 2>/dev/null ||
    { echo "$header says it throws aief::Error but does not declare it"; status=1; }
done
exit $status
