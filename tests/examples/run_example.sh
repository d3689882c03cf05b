#!/bin/sh
# Runs one example of examples/ as a user would, at --size tiny, and checks its report
# (check_report.py). usage: run_example.sh exec_python|answers_file|plugin_cmake CERTCYL SOURCE_DIR WORK_DIR
#                           run_example.sh plugin_fcl CERTCYL SOURCE_DIR WORK_DIR PLUGIN_FCL_SO
set -eu
example=$1 certcyl=$2 src=$3 work=$4
python=${PYTHON:-/usr/bin/python3}
cmake=${CMAKE:-cmake}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work"
cd "$work"
case $example in
  exec_python)
    # The program answers a line as soon as it is read: one line in, its answer out, while its
    # input stays open.
    "$python" - "$src/examples/exec_python/line_double.py" <<'PY'
import json, select, subprocess, sys
p = subprocess.Popen([sys.executable, sys.argv[1]], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
p.stdin.write(json.dumps({"id": "q", "query": "ray_cylinder", "ray": {"origin": [0, 0, 5], "direction": [0, 0, -1]},
                          "cylinder": {"p0": [0, 0, 0], "p1": [0, 0, 1], "radius": 1}}) + "\n")
p.stdin.flush()
ready = select.select([p.stdout], [], [], 20)[0]
answer = json.loads(p.stdout.readline()) if ready else None
p.kill()
if answer != {"id": "q", "answer": "overlapping"}:
    sys.exit("FAIL: one line, its input left open, answered %r" % (answer,))
PY
    command="$python $src/examples/exec_python/line_double.py"
    "$certcyl" judge --exec "$command" --query ray_cylinder --size tiny --timeout 30 > out.txt
    "$python" "$here/check_report.py" "$certcyl" results/judge "$command"
    ;;
  answers_file)
    PYTHON=$python sh "$src/examples/answers_file/judge_answers.sh" "$certcyl" > out.txt
    [ -s cases.jsonl ] && [ -s mine.jsonl ] || { echo "FAIL: no cases or answers file"; exit 1; }
    # The map cells answered in the file give the maps, and the rounding near the wall fails there.
    wrong=$(awk -F, 'NR > 1 { w += $8 } END { print w + 0 }' results/mine/failure_maps.csv)
    [ "$wrong" -gt 0 ] || { echo "FAIL: the answers file's maps record no wrong cell"; exit 1; }
    "$python" "$here/check_report.py" "$certcyl" results/mine mine
    ;;
  plugin_cmake)
    # The snippet, configured and built on its own against the header folder.
    "$cmake" -S "$src/examples/plugin_cmake" -B build -DCERTCYL_INCLUDE_DIR="$src/include" > cmake.txt
    "$cmake" --build build > build.txt
    "$certcyl" judge --plugin build/my_plugin.so --size tiny > out.txt
    "$python" "$here/check_report.py" "$certcyl" results/judge my_plugin
    ;;
  plugin_fcl)
    # FCL as a plugin, built with the project: judged under the name it gives itself, the report
    # checked, then against the certified cases (check_plugin_fcl.py).
    plugin=$5
    name=$("$python" -c 'import ctypes, sys
f = ctypes.CDLL(sys.argv[1]).certcyl_plugin_name
f.restype = ctypes.c_char_p
print(f().decode())' "$plugin")
    "$certcyl" judge --plugin "$plugin" --size tiny --out results > out.txt
    "$python" "$here/check_report.py" "$certcyl" results/judge "$name"
    "$python" "$here/check_plugin_fcl.py" "$certcyl" results/judge "$plugin" tiny
    ;;
  *)
    echo "unknown example $example"
    exit 2
    ;;
esac
