#!/bin/sh
# What --display-server costs a render: the same render alternately without and with streaming to a
# stand-in tev (tools/tev_sink.py, on 127.0.0.1), N runs each, in one session so both see the same
# machine. Prints each run's render seconds (the summary line) and process CPU seconds, then the
# medians and their ratios.
#   tools/display_server_cost.sh [BINARY] [RUNS] [SPP]    (defaults: build/penumbra, 5, 64)
set -eu
BIN=${1:-build/penumbra}
RUNS=${2:-5}
SPP=${3:-64}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SCENE="$ROOT/scenes/hw2/Tests/sphere-area.xml"
OUT=$(mktemp -d)
trap 'kill "$SINK" 2>/dev/null || true; rm -rf "$OUT"' EXIT
python3 "$ROOT/tools/tev_sink.py" > "$OUT/sink.log" &
SINK=$!
for _ in 1 2 3 4 5 6 7 8 9 10; do grep -q listening "$OUT/sink.log" 2>/dev/null && break; sleep 0.2; done
ADDR=$(sed -n 's/^listening on //p' "$OUT/sink.log")
[ -n "$ADDR" ] || { echo "tev_sink.py did not start" >&2; exit 1; }
run() {  # $1: label, rest: extra arguments
  label=$1; shift
  /usr/bin/time -f "%U %S" -o "$OUT/time" "$BIN" render "$SCENE" --spp "$SPP" --threads 2 -o "$OUT/x.pfm" "$@" \
    > "$OUT/line" 2> "$OUT/err"
  secs=$(sed -n 's/.* spp, \([0-9.]*\) s,.*/\1/p' "$OUT/line")
  cpu=$(awk '{print $1 + $2}' "$OUT/time")
  echo "$label $secs $cpu" | tee -a "$OUT/results"
  if grep -q warning "$OUT/err"; then cat "$OUT/err" >&2; fi
}
echo "run render_seconds cpu_seconds"
for i in $(seq "$RUNS"); do
  run off
  run stream --display-server "$ADDR"
done
kill "$SINK" 2>/dev/null || true
sleep 0.2
echo "sink: $(grep -c connection "$OUT/sink.log") connections, bytes each: $(sed -n 's/.*: \([0-9]*\) bytes/\1/p' "$OUT/sink.log" | tr '\n' ' ')"
awk '
  function median(a, n,   i, j, t) {
    for (i = 2; i <= n; i++) { t = a[i]; for (j = i - 1; j > 0 && a[j] > t; j--) a[j + 1] = a[j]; a[j + 1] = t }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
  }
  $1 == "off" { ow[++o] = $2; oc[o] = $3 }
  $1 == "stream" { sw[++s] = $2; sc[s] = $3 }
  END {
    mow = median(ow, o); msw = median(sw, s); moc = median(oc, o); msc = median(sc, s)
    printf "median render seconds: off %.3f  stream %.3f  ratio %.4f\n", mow, msw, msw / mow
    printf "median CPU seconds:    off %.3f  stream %.3f  ratio %.4f\n", moc, msc, msc / moc
  }' "$OUT/results"
