# Sourced by the shell checks: one JUnit result with one test case, as scripts/test counts them.
#   junit_result OUT SUITE CLASS NAME FAILURE     (FAILURE empty: passed)
# xml_text TEXT: TEXT fit for an XML attribute (markup characters and a log's colour codes out)
xml_text() { tr -d '\000-\037' <<<"$1" | sed 's/\[[0-9;]*m//g; s/[<>&"]/_/g'; }
junit_result() {
  local out=$1 suite=$2 class=$3 name=$4 failure=$5
  mkdir -p "$(dirname "$out")"
  {
    echo '<?xml version="1.0" encoding="UTF-8"?>'
    echo "<testsuite name=\"$suite\" tests=\"1\" failures=\"$([ -z "$failure" ] && echo 0 || echo 1)\">"
    echo "  <testcase classname=\"$class\" name=\"$name\">"
    [ -z "$failure" ] || echo "    <failure message=\"$(xml_text "$failure")\"/>"
    echo '  </testcase>'
    echo '</testsuite>'
  } >"$out"
}
