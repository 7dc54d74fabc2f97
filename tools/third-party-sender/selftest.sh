#!/usr/bin/env bash
# Self-test of the CNCjs harness against fake_grbl.py on a socat pty pair:
#  1. plain grbl program (400 lines, slow board): the fake must see exactly the
#     file's lines in order (plus CNCjs's closing "G4 P0.5") and never more than
#     128 unanswered bytes, and the buffer must really fill (character counting);
#  2. FANUC-dialect program: what CNCjs sends must equal testdata/fanuc.expected
#     (pins down how CNCjs rewrites FANUC text: see README);
#  3. the board answers error:20 to a line -> run.sh must exit 1;
#  4. the board raises ALARM after CNCjs's "G4 P0.5" -> run.sh must exit 1;
#  5. the board refuses `$G` while running (error:8) -> run.sh must exit 1.
# Needs setup.sh to have run (CNCjs in node_modules) and socat. Prints
# "N passed, N failed"; exits non-zero if any case failed. KEEP=1 keeps the logs.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
work="$(mktemp -d /tmp/third-party-sender.XXXXXX)"
passed=0
failed=0
pids=()

cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null; done
  wait 2>/dev/null
}
trap cleanup EXIT

command -v socat >/dev/null || { echo "selftest: socat is missing (run setup.sh)" >&2; exit 1; }
[ -d "$here/node_modules/cncjs" ] || { echo "selftest: CNCjs missing (run setup.sh)" >&2; exit 1; }

# run_case NAME GCODE WANT_RC [fake_grbl args...]: socat pair + fake + run.sh.
# Leaves $work/NAME/{report.json,fake.log,run.log}; sets $rc.
run_case() {
  local name=$1 gcode=$2 want=$3
  shift 3
  local d="$work/$name"
  mkdir -p "$d"
  socat "pty,raw,echo=0,link=$d/board" "pty,raw,echo=0,link=$d/sender" 2>"$d/socat.log" &
  local sp=$!
  pids+=("$sp")
  for _ in $(seq 100); do [ -e "$d/board" ] && [ -e "$d/sender" ] && break; sleep 0.05; done
  python3 "$here/fake_grbl.py" "$d/board" --log "$d/fake.log" --report "$d/report.json" "$@" &
  local fp=$!
  pids+=("$fp")
  sleep 0.3
  # Cases 3-5 fail on purpose: keep CNCjs's server log only when KEEP is set.
  SENDER_KEEP_LOG="${KEEP:-0}" "$here/run.sh" "$d/sender" "$gcode" --timeout 120 >"$d/run.log" 2>&1
  rc=$?
  kill "$fp"; wait "$fp" 2>/dev/null
  kill "$sp"; wait "$sp" 2>/dev/null
  if [ "$rc" -ne "$want" ]; then
    fail "$name" "run.sh exited $rc, want $want: $(tail -n 1 "$d/run.log")"
    return 1
  fi
}

pass() { echo "PASS $1: $2"; passed=$((passed + 1)); }
fail() { echo "FAIL $1: $2"; sed 's/^/    /' "$work/$1/run.log" 2>/dev/null | tail -n 5; failed=$((failed + 1)); }

# check NAME EXPECTED_FILE MIN_FILL: compare the fake's record with the expectation.
check() {
  local name=$1 expected=$2 min_fill=$3 verdict
  verdict="$(python3 - "$work/$name/report.json" "$expected" "$min_fill" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
want = [l for l in open(sys.argv[2]).read().split("\n") if l != ""]
got = report["program_lines"]
fill = report["max_unanswered"]
problems = []
if got != want:
    first = next((i for i, (a, b) in enumerate(zip(got, want)) if a != b), min(len(got), len(want)))
    problems.append(f"lines differ at {first + 1}: got {got[first:first + 1]} want {want[first:first + 1]} "
                    f"({len(got)} got, {len(want)} wanted)")
if report["overflows"] or fill > report["rx_buffer"]:
    problems.append(f"receive buffer overflowed: {fill} bytes unanswered > {report['rx_buffer']}")
if fill < int(sys.argv[3]):
    problems.append(f"buffer never filled: at most {fill} bytes in flight (< {sys.argv[3]})")
print("; ".join(problems) or f"{len(got)} lines in order, at most {fill}/128 bytes unanswered, "
      f"commands {sorted(set(report['commands']))}, real-time {report['realtime']}")
sys.exit(1 if problems else 0)
PY
)" && pass "$name" "$verdict" || fail "$name" "$verdict"
}

# 1. plain grbl program: lines of 5..70 characters so the 128-byte window fills.
python3 - "$work/plain.nc" "$work/plain.expected" <<'PY'
import sys
lines = ["G21 G90 G94"]
for i in range(400):
    x, z = (i * 37) % 500 / 10, -((i * 53) % 900) / 10
    pad = " F%d.%03d" % (100 + i % 50, i % 1000) * (i % 4)
    lines.append(f"G1 X{x:.3f} Z{z:.3f}{pad}")
lines.append("M30")
open(sys.argv[1], "w").write("\n".join(lines) + "\n")
open(sys.argv[2], "w").write("\n".join(lines + ["G4 P0.5"]) + "\n")
PY
run_case plain "$work/plain.nc" 0 --line-ms 4 && check plain "$work/plain.expected" 64

# 2. FANUC dialect: CNCjs's rewriting is pinned in testdata/fanuc.expected; the
#    fake answers ?, $G, $I in our board's formats (docs/PROTOCOL.md) this time.
run_case fanuc "$here/testdata/fanuc.nc" 0 --board-format &&
  check fanuc "$here/testdata/fanuc.expected" 0

# 3. an error from the board fails the run.
printf 'G21 G90\nG1 X1 Z-1 F100\nG1 X7.77 Z-2\nG1 X3 Z-3\nM30\n' >"$work/error.nc"
run_case error "$work/error.nc" 1 --error-on X7.77 &&
  pass error "board error:20 -> run.sh exit 1 ($(tail -n 1 "$work/error/run.log"))"

# 4. a board that alarms on CNCjs's closing "G4 P0.5" (FANUC: P takes no decimal point).
run_case alarm "$work/error.nc" 1 --alarm-on "G4 P0.5" &&
  pass alarm "board ALARM -> run.sh exit 1 ($(tail -n 1 "$work/alarm/run.log"))"

# 5. a board that refuses `$G` while running (error:8): CNCjs polls `$G` every
#    ~0.5 s during the job and takes the error as the program's -> run.sh exit 1.
run_case strict "$work/plain.nc" 1 --line-ms 4 --strict-dollar &&
  pass strict "\$G refused in Run -> run.sh exit 1 ($(tail -n 1 "$work/strict/run.log"))"

echo "$passed passed, $failed failed"
if [ "$failed" -eq 0 ] && [ -z "${KEEP:-}" ]; then rm -rf "$work"; else echo "selftest: files kept in $work"; fi
[ "$failed" -eq 0 ]
