#!/usr/bin/env bash
# The command under faults (ctest label 'faults'): signals, closed and full outputs, hostile
# input, pathological scenes. Each case asserts the exit status, the message and that no
# complete output line was lost or cut. Usage: faults.sh CERTCYL_BINARY
set -uo pipefail
certcyl=${1:?usage: faults.sh CERTCYL_BINARY}
py=/usr/bin/python3
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok:   $*"; }

# Every line of $1 is a complete JSON object; prints the number of lines.
complete_lines() {
  "$py" - "$1" <<'EOF'
import json, sys
data = open(sys.argv[1], 'rb').read()
if data and not data.endswith(b'\n'):
    sys.exit('a cut line at the end')
for n, line in enumerate(data.splitlines(), 1):
    json.loads(line)
print(len(data.splitlines()))
EOF
}

cyl='{"p0":[0,0,0],"p1":[0,0,1],"radius":1}'

# 1. A floating method whose products overflow: an answer, never a signal.
out=$(echo '{"id":1,"query":"line_cylinder","line":{"origin":[0,0,0],"direction":[1e300,0,0]},"cylinder":'"$cyl"'}' |
  "$certcyl" query --method robust_double)
status=$?
if [[ $status == 0 && $out == *'"answer":"invalid"'* && $out == *'"reason":"non-finite value in interval[0].approx"'* ]]; then
  pass "overflow in robust_double answers invalid"
else fail "overflow in robust_double: status $status, $out"; fi

# 2. SIGINT in the middle of a long run: exit 130, every answered line complete and in order.
"$py" - > "$work/many.jsonl" <<'EOF'
import json
for i in range(200000):
    print(json.dumps({"id": i, "query": "cylinder_cylinder",
                      "a": {"p0": [0, 0, 0], "p1": [0, 0, 2], "radius": 1},
                      "b": {"p0": [2, 0, i % 7], "p1": [2, 1, 3], "radius": 1}}))
EOF
for threads in 1 2; do
  "$certcyl" query --threads $threads < "$work/many.jsonl" > "$work/int.out" 2> "$work/int.err" &
  pid=$!
  sleep 1.5
  kill -INT $pid
  wait $pid
  status=$?
  n=$(complete_lines "$work/int.out")
  ordered=$("$py" -c "
import json,sys
ids=[json.loads(l)['id'] for l in open('$work/int.out')]
print(ids == list(range(len(ids))))")
  if [[ $status == 130 && $n -gt 0 && $n -lt 200000 && $ordered == True ]]; then
    pass "SIGINT during query --threads $threads: exit 130, $n complete lines in order"
  else fail "SIGINT during query --threads $threads: status $status, lines $n, in order $ordered"; fi
done

# 3. SIGTERM while waiting for input: exit 143 at once; the line answered before is out.
mkfifo "$work/fifo"
"$certcyl" query < "$work/fifo" > "$work/wait.out" &
pid=$!
exec 7> "$work/fifo"
echo '{"id":"first","query":"point_cylinder","point":[0,0,0.5],"cylinder":'"$cyl"'}' >&7
for _ in $(seq 50); do [[ -s $work/wait.out ]] && break; sleep 0.1; done
kill -TERM $pid
wait $pid
status=$?
exec 7>&-
if [[ $status == 143 && $(cat "$work/wait.out") == *'"id":"first","answer":"overlapping"'* ]]; then
  pass "a co-process gets its answer before more input; SIGTERM while waiting exits 143"
else fail "co-process/SIGTERM: status $status, output $(cat "$work/wait.out")"; fi

# 4. A closed output (SIGPIPE ignored): exit 1 with a message, not death by signal.
"$certcyl" query < "$work/many.jsonl" 2> "$work/pipe.err" | head -1 > /dev/null
status=${PIPESTATUS[0]}
if [[ $status == 1 && $(cat "$work/pipe.err") == *"error writing standard output"* ]]; then
  pass "query into a closed pipe: exit 1 with a message"
else fail "query into a closed pipe: status $status, $(cat "$work/pipe.err")"; fi

# 5. A full device: every writing command says so and exits 1.
if [[ -w /dev/full ]]; then
  head -300 "$work/many.jsonl" | "$certcyl" query > /dev/full 2> "$work/full.err"
  status=$?
  [[ $status == 1 && $(cat "$work/full.err") == *"error writing standard output"* ]] &&
    pass "query > /dev/full: exit 1 with a message" || fail "query > /dev/full: status $status"
  "$certcyl" make-scene --cylinders 1000 > /dev/full 2> "$work/full.err"
  status=$?
  [[ $status == 1 && $(cat "$work/full.err") == *"error writing standard output"* ]] &&
    pass "make-scene > /dev/full: exit 1 with a message" || fail "make-scene > /dev/full: status $status"
  "$certcyl" demo > /dev/full 2> "$work/full.err"
  status=$?
  [[ $status == 1 && $(cat "$work/full.err") == *"error writing standard output"* ]] &&
    pass "demo > /dev/full: exit 1 with a message" || fail "demo > /dev/full: status $status"
  "$certcyl" make-scene --cylinders 500 --seed 3 > "$work/small_scene.json"
  "$certcyl" scene "$work/small_scene.json" > /dev/full 2> "$work/full.err"
  status=$?
  [[ $status == 1 && $(cat "$work/full.err") == *"error writing standard output"* ]] &&
    pass "scene > /dev/full: exit 1 with a message" || fail "scene > /dev/full: status $status"
else
  echo "skip: no writable /dev/full"
fi

# 6. A pathological scene: 10,000 identical cylinders (5 * 10^7 overlapping pairs). The scan
# streams: memory stays that of the scene while lines pour out; SIGINT ends it with complete lines.
"$py" -c "
import json
print(json.dumps({'cylinders': [{'name': 'c%d' % i, 'p0': [0, 0, 0], 'p1': [0, 0, 1], 'radius': 1} for i in range(10000)]}))
" > "$work/identical.json"
"$certcyl" scene --threads 2 "$work/identical.json" > "$work/identical.out" 2> "$work/identical.err" &
pid=$!
sleep 4
peak_kb=$(awk '/VmHWM/ {print $2}' /proc/$pid/status)
kill -INT $pid
wait $pid
status=$?
n=$(complete_lines "$work/identical.out")
if [[ $status == 130 && $n -gt 10000 && $peak_kb -lt 262144 ]]; then
  pass "10,000 identical cylinders: $n lines in 4 s, peak memory $((peak_kb / 1024)) MiB, SIGINT exit 130, no cut line"
else fail "identical cylinders: status $status, lines $n, peak ${peak_kb} kB"; fi

# 7. Hostile lines, each its own error naming what is wrong, the others answered.
{
  echo '{"id":1,"query":"point_cylinder","point":[0,0,0.5],"cylinder":'"$cyl"'}'
  "$py" -c "print('[' * 100000 + ']' * 100000)"
  "$py" -c "print('{\"id\": 2, \"query\": \"point_cylinder\", \"point\": [\"' + '9' * 30000 + '\", 0, 0], \"cylinder\": $cyl}')"
  "$py" -c "print('x' * 3000000)"
  echo '{"id":3,"query":"point_cylinder","point":[0,0,0.5],"cylinder":'"$cyl"',"cylinder":'"$cyl"'}'
  echo '{"id":4,"query":"point_cylinder","point":[0,0,0.5],"cylinder":'"$cyl"'}'
} > "$work/hostile.jsonl"
"$certcyl" query < "$work/hostile.jsonl" > "$work/hostile.out"
status=$?
expected=$(cat <<'EOF'
{"id":1,"answer":"overlapping"}
{"id":null,"line":2,"error":"malformed JSON: nested deeper than 16 levels"}
{"id":2,"line":3,"error":"point[0]: exact number of 99659 bits (numerator and denominator); the limit is 65536 (about 19,700 decimal digits)"}
{"id":null,"line":4,"error":"line longer than the limit of 1048576 bytes"}
{"id":3,"line":5,"error":"malformed JSON: member \"cylinder\" appears twice in one object"}
{"id":4,"answer":"overlapping"}
EOF
)
got=$("$py" -c "
import json
for l in open('$work/hostile.out'):
    j = json.loads(l)
    print(json.dumps({k: j[k] for k in ('id', 'line', 'error', 'answer') if k in j}, separators=(',', ':')))")
if [[ $status == 2 && $got == "$expected" ]]; then
  pass "hostile lines: one exact error each, the others answered"
else fail "hostile lines: status $status"; diff <(echo "$expected") <(echo "$got"); fi

# 8. Bad options and files: a clear message, exit 1 (usage) or 2 (invalid scene).
check_message() {  # expected-status expected-substring command...
  local want=$1 text=$2
  shift 2
  "$@" > /dev/null 2> "$work/opt.err" < /dev/null
  local status=$?
  if [[ $status == "$want" && $(cat "$work/opt.err") == *"$text"* ]]; then pass "$* -> $status: $text"
  else fail "$*: status $status, stderr $(head -c 300 "$work/opt.err")"; fi
}
check_message 1 "--nt: unknown number type 'floaty'" "$certcyl" query --nt floaty
check_message 1 "--cylinders: Value -5 not in range" "$certcyl" make-scene --cylinders -5
check_message 1 "--threads: Value -1 not in range" "$certcyl" query --threads -1
for limit in -1 abc nan inf 1e10; do
  check_message 1 "--time-limit: expected a number of seconds in [0, 1e9] (0: no limit), got '$limit'" "$certcyl" query --time-limit "$limit"
done
check_message 1 "cannot open '$work/none.json': No such file or directory" "$certcyl" scene "$work/none.json"
echo '{"cylinders": [{"name": "a", "p0": [0,0,0], "p1": [0,0,1], "radius": 1}, {"name": "a", "p0": [5,0,0], "p1": [5,0,1], "radius": 1}]}' > "$work/dup.json"
check_message 2 'cylinders[1]: name "a" is also the name of cylinders[0]' "$certcyl" scene "$work/dup.json"
"$py" -c "print('{\"cylinders\": ' + '[' * 100000 + ']' * 100000 + '}')" > "$work/deep.json"
check_message 2 "nested deeper than 16 levels" "$certcyl" scene "$work/deep.json"

# 9. CORE::Expr ends its process on some inputs (exit(1) from a BigFloat division, SIGFPE from
# GMP): the line is answered "invalid" with the reason, every other line is answered, and no
# Core_Diagnostics file is left in the working directory.
good_line='{"id":"g%s","query":"line_cylinder","line":{"origin":[0,0,0.5],"direction":[1,0,0]},"cylinder":'"$cyl"'}'
core_line='{"id":43,"query":"line_cylinder","line":{"origin":[0,3.0,1.7976931348623157e+308],"direction":[1e+154,-1,1e+154]},"cylinder":{"p0":[-1,-1,-1e+300],"p1":[-1e+300,-1.7976931348623157e+308,1e+154],"radius":5e-324}}'
fpe_line='{"id":906,"query":"cylinder_cylinder","a":{"p0":[1.7976931348623157e+308,1e-300,3.0],"p1":[1e-160,3.0,-1e+300],"radius":1.7976931348623157e+308},"b":{"p0":[-1e+300,-1e+300,5e-324],"p1":[5e-324,-1.7976931348623157e+308,1e+300],"radius":1.7976931348623157e+308}}'
mkdir -p "$work/cwd"
{ printf "$good_line\n" 1; printf "$good_line\n" 2; echo "$core_line"; printf "$good_line\n" 3; } > "$work/core.jsonl"
for threads in 1 2; do
  (cd "$work/cwd" && "$certcyl" query --method shene --nt core_expr --threads $threads < "$work/core.jsonl" > "$work/core.out" 2> "$work/core.err")
  status=$?
  got=$("$py" -c "
import json
for l in open('$work/core.out'):
    j = json.loads(l)
    print(j['id'], j['answer'], j.get('reason', ''))")
  expected=$(printf '%s\n' 'g1 overlapping ' 'g2 overlapping ' '43 invalid CORE::Expr ended the computation: BigFloat error: possible zero divisor.' 'g3 overlapping ')
  if [[ $status == 0 && $got == "$expected" && ! -e $work/cwd/Core_Diagnostics && ! -s $work/core.err ]]; then
    pass "shene in core_expr, --threads $threads: CORE's exit is an invalid answer, the other lines kept"
  else fail "shene in core_expr --threads $threads: status $status, Core_Diagnostics $(ls "$work/cwd")"; diff <(echo "$expected") <(echo "$got"); fi
done
{ printf "$good_line\n" 1 | sed 's/"query":"line_cylinder","line":{"origin":\[0,0,0.5\],"direction":\[1,0,0\]},"cylinder"/"query":"cylinder_cylinder","a":{"p0":[0,0,0],"p1":[0,0,1],"radius":1},"b"/'
  echo "$fpe_line"; } > "$work/fpe.jsonl"
(cd "$work/cwd" && "$certcyl" query --method eberly_corrected --nt core_expr < "$work/fpe.jsonl" > "$work/fpe.out" 2> "$work/fpe.err")
status=$?
got=$("$py" -c "
import json
for l in open('$work/fpe.out'):
    j = json.loads(l)
    print(j['id'], j['answer'], j.get('reason', ''))")
expected=$(printf '%s\n' 'g1 overlapping ' '906 invalid the computation ended by signal 8 (Floating point exception)')
if [[ $status == 0 && $got == "$expected" && ! -e $work/cwd/Core_Diagnostics ]]; then
  pass "eberly_corrected in core_expr: SIGFPE is an invalid answer, the line before kept"
else fail "eberly_corrected in core_expr: status $status"; diff <(echo "$expected") <(echo "$got"); fi

# 10. A file that opens but cannot be read (a directory): "read error" naming it, exit 1; the
# lines answered before are kept.
mkdir -p "$work/adir"
check_message 1 "certcyl scene: read error: '$work/adir': Is a directory" "$certcyl" scene "$work/adir"
"$certcyl" query < "$work/adir" > "$work/dir.out" 2> "$work/dir.err"
status=$?
if [[ $status == 1 && $(cat "$work/dir.err") == "certcyl query: read error: standard input: Is a directory" && ! -s $work/dir.out ]]; then
  pass "query < a directory: exit 1, read error"
else fail "query < a directory: status $status, $(cat "$work/dir.err")"; fi

# 11. judge: a full output, a --name outside --out; merge without shards: messages on stderr.
"$certcyl" cases --query line_cylinder --size 2 > "$work/cases.jsonl" 2> /dev/null
"$certcyl" query < "$work/cases.jsonl" > "$work/answers.jsonl"
if [[ -w /dev/full ]]; then
  "$certcyl" judge --cases "$work/cases.jsonl" --answers "$work/answers.jsonl" --out "$work/j" > /dev/full 2> "$work/full.err"
  status=$?
  [[ $status == 1 && $(cat "$work/full.err") == *"certcyl judge: error writing standard output"* ]] &&
    pass "judge > /dev/full: exit 1 with a message" || fail "judge > /dev/full: status $status, $(cat "$work/full.err")"
fi
for name in ../escaped "$work/abs" ""; do
  check_message 1 "--name: expected a plain folder name (not empty, no '/', not starting with '.'), got '$name'" \
    "$certcyl" judge --cases "$work/cases.jsonl" --answers "$work/answers.jsonl" --out "$work/j" --name "$name"
done
[[ ! -e $work/escaped && ! -e $work/abs ]] && pass "judge --name: nothing written outside --out" || fail "judge --name wrote outside --out"
mkdir -p "$work/noshards"
"$certcyl" merge "$work/noshards" > "$work/merge.out" 2> "$work/merge.err"
status=$?
if [[ $status == 1 && ! -s $work/merge.out && $(cat "$work/merge.err") == *"merge: no shard-*-of-* folders in $work/noshards"* ]]; then
  pass "merge without shards: the error on standard error, exit 1"
else fail "merge without shards: status $status, stdout $(cat "$work/merge.out")"; fi

# 12. Options: a negative seed is not wrapped, NaN is not a number in range.
check_message 1 "--seed: expected an integer in [0, 18446744073709551615], got '-1'" "$certcyl" cases --query line_cylinder --seed -1
check_message 1 "--seed: expected an integer in [0, 18446744073709551615], got '-1'" \
  "$certcyl" judge --query line_cylinder --answers "$work/answers.jsonl" --seed -1
check_message 1 "--touching: expected a finite number in [0, 1], got 'nan'" "$certcyl" make-scene --cylinders 10 --touching nan
check_message 1 "--neighbours: expected a finite number in [0.01, 1000], got 'nan'" "$certcyl" make-scene --cylinders 10 --neighbours nan
check_message 1 "--timeout: expected a finite number in [0, 1e+06], got 'nan'" \
  "$certcyl" judge --cases "$work/cases.jsonl" --answers "$work/answers.jsonl" --out "$work/j" --timeout nan

# 13. A key given twice: an error naming it, never the last one winning.
echo '{"per_family": 1, "per_family": 2}' > "$work/dup_config.json"
check_message 1 "--config: '$work/dup_config.json': member \"per_family\" appears twice in one object" \
  "$certcyl" study --config "$work/dup_config.json" --out "$work/r" --no-plots --no-progress
head -1 "$work/answers.jsonl" | sed 's/"answer":"\([a-z]*\)"/"answer":"\1","answer":"separated"/' > "$work/dup_answers.jsonl"
tail -n +2 "$work/answers.jsonl" >> "$work/dup_answers.jsonl"
check_message 1 "dup_answers.jsonl line 1: member \"answer\" appears twice in one object" \
  "$certcyl" judge --cases "$work/cases.jsonl" --answers "$work/dup_answers.jsonl" --out "$work/j"

# 14. merge reads only regular files of the listed size: a symbolic link (to /dev/zero, to the
# folder itself) or a FIFO in a shard is refused, naming it, before anything is read or written.
echo '{"per_family": 1, "map_cells": 2, "hunt_evaluations": 1, "methods": ["robust/double"]}' > "$work/small_config.json"
for i in 0 1; do
  "$certcyl" study --config "$work/small_config.json" --shard $i/2 --out "$work/r" --name m --no-plots --no-progress > /dev/null 2>&1
done
if [[ -f $work/r/m/shard-0-of-2/manifest.json && -f $work/r/m/shard-1-of-2/manifest.json ]]; then
  cp -r "$work/r/m" "$work/r/good"
  "$certcyl" merge "$work/r/good" --no-plots > /dev/null 2> "$work/merge.err" &&
    pass "merge of two shards" || fail "merge of two shards: $(cat "$work/merge.err")"
  damage() {  # label, what to do in the shard, expected message, the shard (default shard-0-of-2)
    local shard=${4:-shard-0-of-2}
    rm -rf "$work/r/d"
    cp -r "$work/r/m" "$work/r/d"
    (cd "$work/r/d/$shard" && eval "$2")
    local before=$(du -sk "$work/r/d" | cut -f1)
    (ulimit -f 20000; timeout 20 "$certcyl" merge "$work/r/d" --no-plots > /dev/null 2> "$work/merge.err")
    local status=$?
    local after=$(du -sk "$work/r/d" | cut -f1)
    if [[ $status == 1 && $(cat "$work/merge.err") == "certcyl: merge: $shard/$3" && $after == "$before" ]]; then pass "merge refuses $1"
    else fail "merge with $1: status $status, $before -> $after kB, $(head -c 300 "$work/merge.err")"; fi
  }
  damage "a link to /dev/zero" "rm hunt.csv && ln -s /dev/zero hunt.csv" \
    "hunt.csv: a symbolic link, not a regular file of the size its manifest lists"
  # Shard 1 has no failure maps, so its manifest lists none: the link alone led the copy of
  # failure_maps into the merged folder, and so into itself.
  damage "a link to the folder" "ln -s .. failure_maps" \
    "failure_maps: a symbolic link, not a regular file of the size its manifest lists" shard-1-of-2
  damage "a FIFO" "mkfifo hunt.csv.fifo" \
    "hunt.csv.fifo: a FIFO, not a regular file of the size its manifest lists"
else
  fail "study --shard did not write two shards"
fi

# 15. Eberly's seed on perpendicular cylinders at 1e300: a overlaps b (the point (0, 0, 5e299) is
# at distance 5e299 < 1e300 from both axes, inside both axis segments), but |p1 - p0| = 2e300
# squared overflows double, so the unit axes came out zero, the axes looked parallel and the
# radial test answered "separated". Both variants now answer invalid, naming the value; long
# double holds 4e600 and gets the answer right.
big='{"id":1,"query":"cylinder_cylinder","a":{"p0":[-1e300,0,0],"p1":[1e300,0,0],"radius":1e300},"b":{"p0":[0,-1e300,1e300],"p1":[0,1e300,1e300],"radius":1e300}}'
for method in eberly_corrected eberly_as_written; do
  out=$(echo "$big" | "$certcyl" query --method $method)
  status=$?
  if [[ $status == 0 && $out == *'"answer":"invalid"'* && $out == *'"reason":"non-finite value in h0"'* ]]; then
    pass "$method on perpendicular cylinders at 1e300: invalid, h0 named"
  else fail "$method at 1e300: status $status, $out"; fi
done
out=$(echo "$big" | "$certcyl" query --method eberly_corrected --nt long_double)
[[ $out == *'"answer":"overlapping"'* ]] && pass "eberly_corrected in long double at 1e300: overlapping" ||
  fail "eberly_corrected in long double at 1e300: $out"

# 16. make-scene streams: 1,000,000 cylinders (171 MB of JSON text, more than the limit itself,
# so a document held in memory could not fit) under a 128 MiB address-space limit, every
# cylinder written (one '{' each, one for the document) and the document closed.
( ulimit -v 131072; exec "$certcyl" make-scene --cylinders 1000000 --seed 5 ) 2> "$work/big_scene.err" |
  "$py" -c "
import sys
n = 0; tail = b''
for block in iter(lambda: sys.stdin.buffer.read(1 << 20), b''):
    n += block.count(b'{'); tail = (tail + block)[-4:]
print(n, tail.endswith(b']}\\n'))" > "$work/big_scene.out"
status=${PIPESTATUS[0]}
if [[ $status == 0 && $(cat "$work/big_scene.out") == "1000001 True" ]]; then
  pass "make-scene --cylinders 1000000 under ulimit -v 128 MiB: every cylinder written"
else fail "make-scene under ulimit -v: status $status, $(cat "$work/big_scene.out") $(head -c 300 "$work/big_scene.err")"; fi

# 17. A study ended by SIGTERM while a CORE::Expr call runs in its child process: exit 143, no
# results folder (only the hidden partial one), no child left behind; a re-run under the same
# name starts clean and finishes. (SIGTERM, not SIGINT: a background job of a non-interactive
# shell starts with SIGINT ignored.)
echo '{"per_family": 2000, "map_cells": 2, "hunt_evaluations": 1, "methods": ["eberly_cylinders/core_expr"]}' > "$work/core_config.json"
"$certcyl" study --config "$work/core_config.json" --out "$work/ri" --name int --no-plots --no-progress > /dev/null 2> "$work/ri.err" &
pid=$!
children=0
for ((k = 0; k < 600 && children == 0; ++k)); do
  sleep 0.1
  kill -0 $pid 2> /dev/null || break
  children=$(pgrep -P $pid | wc -l)
done
kill -TERM $pid 2> /dev/null
wait $pid
status=$?
sleep 0.5
left=$(pgrep -f "$work/core_config.json" | wc -l)
if [[ $children -gt 0 && $status == 143 && ! -e $work/ri/int && -d $work/ri/.int.partial && $left == 0 ]]; then
  pass "SIGTERM during a study's child call: exit 143, no results folder, no child left"
else fail "SIGTERM during a study's child call: children $children, status $status, folders $(ls -A "$work/ri" 2> /dev/null | tr '\n' ' '), left $left"; fi
echo '{"per_family": 1, "map_cells": 2, "hunt_evaluations": 1, "methods": ["robust/double"]}' > "$work/rerun_config.json"
"$certcyl" study --config "$work/rerun_config.json" --out "$work/ri" --name int --no-plots --no-progress > /dev/null 2> "$work/ri.err"
status=$?
if [[ $status == 0 && -f $work/ri/int/manifest.json && ! -e $work/ri/.int.partial && ! -e $work/ri/int/Core_Diagnostics ]]; then
  pass "a study re-run after the interruption starts clean"
else fail "study re-run after the interruption: status $status, $(ls -A "$work/ri" "$work/ri/int" 2> /dev/null | tr '\n' ' ') $(head -c 300 "$work/ri.err")"; fi

# 18. GMP memory per line (--memory-limit): the middle line's numbers of 15,000 digits make its
# GMP memory go over 64 KiB, so it is an error line saying so; the lines around it (doubles) are
# answered exactly as without the limit, with 1 and 2 threads, and the run goes on to the end
# (exit 2). A limit that is not a size is a usage error.
"$py" - > "$work/memory.jsonl" <<'EOF'
import json
def pair(i, top0, top1):
    return json.dumps({"id": i, "query": "cylinder_cylinder", "a": {"p0": [0, 0, 0], "p1": [0, 0, top0], "radius": 1},
                       "b": {"p0": [3, 0, 0], "p1": [3, 0, top1], "radius": 1}})
print(pair(1, 2, 2))
print(pair(2, "7" * 14999 + "1", "3" * 14999 + "9"))
print(pair(3, 2, 0.5))
EOF
"$certcyl" query < "$work/memory.jsonl" > "$work/memory_plain.out"
for threads in 1 2; do
  "$certcyl" query --memory-limit 64K --threads $threads < "$work/memory.jsonl" > "$work/memory.out"
  status=$?
  want_error='{"id":2,"line":2,"error":"out of memory answering this line: its GMP memory went over the limit of 65536 bytes (--memory-limit)"}'
  if [[ $status == 2 && $(sed -n 1p "$work/memory.out") == "$(sed -n 1p "$work/memory_plain.out")" &&
        $(sed -n 3p "$work/memory.out") == "$(sed -n 3p "$work/memory_plain.out")" && $(sed -n 2p "$work/memory.out") == "$want_error" &&
        $(wc -l < "$work/memory.out") == 3 && $(sed -n 2p "$work/memory_plain.out") == *'"answer":"separated"'* ]]; then
    pass "--memory-limit 64K --threads $threads: the line over it is an error line, the others answered as without it"
  else fail "--memory-limit --threads $threads: status $status, $(cut -c1-200 "$work/memory.out")"; fi
done
check_message 1 "--memory-limit: expected a number of bytes, optionally with K, M, G or T (KiB, MiB, GiB, TiB), got '12X'" \
  "$certcyl" query --memory-limit 12X

echo "$failures failure(s)"
[[ $failures == 0 ]]
