# Sourced by the shell checks: one JUnit result with one test case, as scripts/test counts them.
#   junit_result OUT SUITE CLASS NAME FAILURE     (FAILURE empty: passed)
junit_result() {
  local out=$1 suite=$2 class=$3 name=$4 failure=$5
  mkdir -p "$(dirname "$out")"
  {
    echo '<?xml version="1.0" encoding="UTF-8"?>'
    echo "<testsuite name=\"$suite\" tests=\"1\" failures=\"$([ -z "$failure" ] && echo 0 || echo 1)\">"
    echo "  <testcase classname=\"$class\" name=\"$name\">"
    [ -z "$failure" ] || echo "    <failure message=\"$(sed 's/[<>&"]/_/g' <<<"$failure")\"/>"
    echo '  </testcase>'
    echo '</testsuite>'
  } >"$out"
}
