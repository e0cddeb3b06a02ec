#!/usr/bin/env bash
# End-to-end tests of penumbra-mpi under mpirun (shared memory only, every step under `timeout`).
# usage: run_case.sh CASE MPIRUN PENUMBRA_MPI PENUMBRA IMAGE_COMPARE SOURCE_DIR
#   equality     K = 1, 2, 3 ranks against the single-process render, every sampler x three strategies,
#                within 1e-6 relative per pixel (spp 37 with blocks of 4: uneven over ranks and blocks)
#   uneven       spp not divisible by the ranks or the block renders exactly that spp; a rank
#                without any block still takes part
#   interrupt    SIGINT (Ctrl-C) and SIGUSR1 to mpirun mid-render: rank 0 writes the partial image of
#                every rank's completed rows, each row equal to the single-process render of its spp
#   interrupt_large  Ctrl-C with mpirun's default kill timeout mid-render of 1280x720: a valid partial
#                image and standard error, no temporary left (a stale one of a dead process removed)
#   stop_continue  Ctrl-Z and fg (SIGTSTP, SIGCONT to mpirun) do not end the render; a SIGCONT alone does
#   killed_rank  a rank killed mid-render ends the job; the existing output is untouched
#   reference    --reference writes a reference (metadata name the ranks) that `converge --reference` reads
#   scene_error  one rank's scene fails to load, or rank 0's output cannot be written: exit 2 before
#                rendering, the existing output is untouched
#   disagreement ranks given different image sizes, scene content (--set, an OBJ file), spp, block,
#                seed, sampler or integrator: exit 2 naming each rank's first differing setting, nothing
#                rendered or written; the same scene under another path agrees
#   argument_error  bad arguments on rank 0 only, rank 1 only, every rank, --help on one rank only, a
#                seed beyond 64 bits: every rank ends with exit 2, the message printed once; the largest
#                64-bit seed renders with that seed
#   write_error  rank 0's write fails after the agreement (the output's directory replaced by a file
#                mid-render): exit 2 through MPI_Abort, the error printed once, the old output untouched
#   start_failure  an MPMD job whose second program is missing, fails, or exits 0 without starting
#                MPI; Ctrl-C while a rank has not started: the job ends, the existing output is untouched
# The fault cases print how long each job took to end ("... in S s").
set -u
case_=$1 MPIRUN=$2 PMPI=$3 PENUMBRA=$4 COMPARE=$5 SRC=$6
export OMPI_MCA_btl=self,vader           # no network beyond this machine
export OMPI_MCA_btl_vader_single_copy_mechanism=none  # works in containers without CMA
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
SCENE=$SRC/scenes/hw2/Tests/sphere-area.xml
SMALL=(--set camera.width=48 --set camera.height=40 --set integrator.nSamples=2)
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
mpi() { local k=$1; shift; timeout -k 5 120 "$MPIRUN" --allow-run-as-root --oversubscribe -np "$k" "$PMPI" "$@"; }
# mpirun in the background, its pid in $pid, killed by a watchdog after 240 s; mpi_wait waits for it
# (exit code in $rc) and ends the watchdog, so that nothing outlives the test.
mpi_bg() {
  local k=$1; shift
  "$MPIRUN" --allow-run-as-root --oversubscribe -np "$k" "$PMPI" "$@" & pid=$!
  (sleep 240 & echo $! >"$T/watchdog"; wait $! && kill -KILL $pid) >/dev/null 2>&1 &
}
mpi_wait() {
  wait $pid; rc=$?
  for i in $(seq 50); do [ -s "$T/watchdog" ] && break; sleep 0.1; done
  kill "$(cat "$T/watchdog")" 2>/dev/null
}
meta() { "$COMPARE" --info "$1" | sed -n "s/^$2=//p"; }
seconds_since() { awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }'; }  # since `date +%s.%N`

# Fault cases. An old output (and standard error image) that no fault may change:
old_output() {
  printf 'old image' >"$T/o.exr"; printf 'old standard error' >"$T/o.stderr.exr"
  sums=$(cd "$T" && sha256sum o.exr o.stderr.exr)
}
# Fails unless the old output is byte-identical, no temporary of it is left and no rank of the job
# (a process whose command line names the output) outlives mpirun (2 s of grace).
check_untouched() {
  [ "$(cd "$T" && sha256sum o.exr o.stderr.exr 2>&1)" = "$sums" ] || fail "$1: the old output changed"
  ! ls "$T" | grep -q "^o\..*tmp-" || fail "$1: a temporary was left: $(ls "$T")"
  for i in $(seq 20); do pgrep -f "$T/o.exr" >/dev/null || return 0; sleep 0.1; done
  pgrep -af "$T/o.exr"; pkill -KILL -f "$T/o.exr"; fail "$1: a rank outlived mpirun"
}
# Runs mpirun with the given arguments under a 60 s timeout: output in $T/err, exit code in $rc,
# seconds to the end in $took. A job still running after 60 s is a hang.
fault_run() {
  local label=$1 t0; shift
  t0=$(date +%s.%N)
  timeout -k 5 60 "$MPIRUN" --allow-run-as-root --oversubscribe "$@" >"$T/err" 2>&1; rc=$?
  took=$(seconds_since "$t0")
  if [ $rc = 124 ] || [ $rc = 137 ]; then cat "$T/err"; fail "$label: still running after 60 s (hung)"; fi
}
# The documented outcome of a refused job: exit code 2, TEXT (a fixed string) printed exactly once,
# the old output untouched.
expect_refusal() {
  local label=$1 text=$2 n
  [ $rc = 2 ] || { cat "$T/err"; fail "$label: exit code $rc, expected 2"; }
  n=$(grep -cF -- "$text" "$T/err")
  [ "$n" = 1 ] || { cat "$T/err"; fail "$label: '$text' printed $n times, expected once"; }
  check_untouched "$label"
  echo "$label: exit 2 in $took s: $(grep -F -- "$text" "$T/err")"
}
# Options of a long render (nothing may be rendered before the refusal: a render would time out).
LONG=(--set camera.width=48 --set camera.height=40 --spp 1000000 --threads 1 -o "$T/o.exr")
# Waits (up to 60 s) for rank 0's first progress line: every rank has completed a pass.
wait_for_progress() {
  for i in $(seq 1 600); do
    grep -q "^progress:" "$T/err" && return 0
    kill -0 $pid 2>/dev/null || break
    sleep 0.1
  done
  cat "$T/err"; kill -KILL $pid; fail "no progress line from rank 0"
}

# Expands inclusive row ranges "a-b,c,..." into H flags (0/1), space-separated.
row_flags() {
  local h=$1 ranges=$2 y p lo hi; local -a out parts
  for ((y = 0; y < h; y++)); do out[y]=0; done
  IFS=, read -ra parts <<<"$ranges"
  for p in "${parts[@]}"; do
    [ -n "$p" ] || continue
    lo=${p%-*} hi=${p#*-}
    for ((y = lo; y <= hi; y++)); do out[y]=1; done
  done
  echo "${out[@]}"
}
# Checks the sample counts of a partial image of 2 ranks with --block 1 and rankPasses n0,n1: rank 0
# rendered the even indices 0, 2, ..., 2n0-2 and rank 1 the odd ones 1, 3, ..., 2n1-1 in every row,
# and index 2n0 (rank 0) or 2n1+1 (rank 1) in its rows of rankRowsAhead: row y has the A(y) smallest
# even and the B(y) smallest odd indices. rowSpp (runs "S*R") must be A + B and spp its minimum. A row
# with A = B or A = B + 1 has the index prefix [0, A + B) and must equal the single-process render of
# that spp; other rows (rank 1 a pass ahead of rank 0 there) are checked for validity only.
# usage: check_partial IMAGE HEIGHT LABEL RENDER_ARGS...
check_partial() {
  local f=$1 h=$2 label=$3; shift 3
  local spp passes runs ahead a b y c n run start A B
  spp=$(meta "$f" spp) passes=$(meta "$f" rankPasses) runs=$(meta "$f" rowSpp) ahead=$(meta "$f" rankRowsAhead)
  a=${passes%,*} b=${passes#*,}
  [ $((a - b)) -le 1 ] && [ $((b - a)) -le 1 ] || fail "$label: rankPasses $passes: more than a round apart"
  local -a f0 f1 rows cls
  if [ -n "$runs" ]; then
    f0=($(row_flags "$h" "${ahead%;*}")) f1=($(row_flags "$h" "${ahead#*;}"))
    y=0
    IFS=, read -ra parts <<<"$runs"
    for run in "${parts[@]}"; do
      for ((n = 0; n < ${run#*\*}; n++)); do rows[y]=${run%%\**}; y=$((y + 1)); done
    done
    [ $y = "$h" ] || fail "$label: rowSpp '$runs' covers $y rows, not $h"
  else
    [ -z "$ahead" ] || fail "$label: rankRowsAhead without rowSpp"
    for ((y = 0; y < h; y++)); do f0[y]=0 f1[y]=0 rows[y]=$spp; done
  fi
  local min=${rows[0]}
  for ((y = 0; y < h; y++)); do
    A=$((a + f0[y])) B=$((b + f1[y])) c=$((A + B))
    [ "${rows[y]}" = $c ] || fail "$label: row $y has rowSpp ${rows[y]}, rankPasses and rankRowsAhead give $c"
    [ $c -ge "$min" ] || min=$c
    if [ $A = $B ] || [ $A = $((B + 1)) ]; then cls[y]=$c; else cls[y]=-$A-$B; fi
  done
  [ "$spp" = "$min" ] || fail "$label: spp $spp is not the least rowSpp $min"
  echo "$label: spp $spp, rankPasses $passes, rowSpp ${runs:-uniform}, rankRowsAhead '${ahead}'"
  start=0
  for ((y = 1; y <= h; y++)); do
    [ $y -lt "$h" ] && [ "${cls[y]}" = "${cls[start]}" ] && continue
    c=${cls[start]}
    if [ "${c:0:1}" = - ]; then
      c=${c#-}
      echo "$label: rows $start..$((y - 1)): the ${c%-*} smallest even and ${c#*-} smallest odd indices, valid only"
    else
      [ -f "$T/one-$c.pfm" ] || timeout 300 "$PENUMBRA" render "$SCENE" "$@" --spp "$c" --threads 2 \
        -o "$T/one-$c.pfm" >/dev/null || fail "$label: single render of $c spp"
      echo -n "$label: rows $start..$((y - 1)) against the single-process render of $c spp: "
      "$COMPARE" "$T/one-$c.pfm" "$f" 1e-6 $start $y || fail "$label: rows $start..$((y - 1)) differ from $c spp"
    fi
    start=$y
  done
  rm -f "$T"/one-*.pfm
}

case $case_ in
equality)
  samplers=$("$PENUMBRA" render "$SCENE" --set sampler.type=none -o "$T/x.pfm" 2>&1 | grep -o "expected one of.*" |
             sed 's/expected one of//; s/[,:()]/ /g')
  [ -n "$samplers" ] || samplers="independent stratified"
  echo "samplers: $samplers"
  for sampler in $samplers; do
    for m in "integrator.measure=solid-angle" "integrator.measure=area" "integrator.type=ao"; do
      args=("${SMALL[@]}" --set "sampler.type=$sampler" --set "$m" --spp 37 --seed 5)
      timeout 120 "$PENUMBRA" render "$SCENE" "${args[@]}" --threads 2 -o "$T/one.pfm" >/dev/null || fail "single render $sampler $m"
      for k in 1 2 3; do
        mpi $k render "$SCENE" "${args[@]}" --threads 1 --block 4 -o "$T/k$k.pfm" >/dev/null || fail "mpirun -np $k ($sampler, $m)"
        echo -n "$sampler $m K=$k: "
        "$COMPARE" "$T/one.pfm" "$T/k$k.pfm" 1e-6 || fail "$sampler $m K=$k differs from the single-process render"
      done
    done
  done ;;
uneven)
  mpi 3 render "$SCENE" "${SMALL[@]}" --spp 37 --threads 1 --block 16 -o "$T/u.exr" >/dev/null || fail "mpirun"
  [ "$(meta "$T/u.exr" spp)" = 37 ] || fail "spp $(meta "$T/u.exr" spp), expected 37"
  [ "$(meta "$T/u.exr" mpiRanks)" = 3 ] || fail "mpiRanks"
  [ -f "$T/u.stderr.exr" ] || fail "no standard error image"
  # 5 spp in blocks of 16 over 2 ranks: rank 1 renders nothing and still joins the reduction.
  timeout 120 "$PENUMBRA" render "$SCENE" "${SMALL[@]}" --spp 5 --threads 1 -o "$T/one.pfm" >/dev/null || fail "single"
  mpi 2 render "$SCENE" "${SMALL[@]}" --spp 5 --threads 1 --block 16 -o "$T/k2.pfm" >/dev/null || fail "mpirun 5 spp"
  "$COMPARE" "$T/one.pfm" "$T/k2.pfm" 1e-6 || fail "5 spp over 2 ranks" ;;
interrupt)
  # Ctrl-C is SIGINT to mpirun: it sends every rank SIGCONT at once, SIGTERM
  # odls_base_sigkill_timeout seconds later and SIGKILL as long again after that, then exits with 1
  # (docs/mpi.md). The grace is made generous here so that no load can make the test fail on time.
  # SIGUSR1 is forwarded to every rank at once and the job exits with 3.
  export OMPI_MCA_odls_base_sigkill_timeout=10
  args=(--set camera.width=96 --set camera.height=80 --seed 7)
  for sig in INT USR1; do
    rm -f "$T/p.exr" "$T/p.stderr.exr"; : >"$T/err"
    mpi_bg 2 render "$SCENE" "${args[@]}" --spp 1000000 --threads 1 --block 1 -o "$T/p.exr" >"$T/out" 2>"$T/err"
    wait_for_progress  # every rank has completed a pass, however loaded the machine
    ranks=$(pgrep -P $pid)
    [ $(echo $ranks | wc -w) = 2 ] || { kill -KILL $pid; fail "SIG$sig: expected 2 rank processes, found '$ranks'"; }
    kill -$sig $pid; t0=$(date +%s.%N)
    mpi_wait
    took=$(seconds_since "$t0")
    echo "SIG$sig: mpirun exit code $rc in $took s after the signal; $(cat "$T/out")"
    for r in $ranks; do  # a zombie (not yet reaped by init) is not running
      if [ -d /proc/$r ] && ! grep -q "^State:.*Z" /proc/$r/status 2>/dev/null &&
         grep -q penumbra-mpi /proc/$r/cmdline 2>/dev/null; then
        fail "SIG$sig: rank process $r outlived mpirun"
      fi
    done
    [ -f "$T/p.exr" ] || { cat "$T/err"; fail "SIG$sig: no partial image"; }
    grep -q "^interrupted (.*): writing the rows" "$T/err" || { cat "$T/err"; fail "SIG$sig: rank 0 did not say it was interrupted"; }
    [ "$(meta "$T/p.exr" interrupted)" = true ] || fail "SIG$sig: metadata lack interrupted=true"
    [ "$(meta "$T/p.exr" valid)" = 1 ] || fail "SIG$sig: invalid pixels"
    [ "$(meta "$T/p.stderr.exr" valid)" = 1 ] || fail "SIG$sig: invalid standard error"
    # With blocks of one sample the ranks stop after the same round; each row has its ranks' passes
    # and, where a rank had completed the row in the interrupted pass, that one more.
    spp=$(meta "$T/p.exr" spp)
    [ "$spp" -ge 2 ] && [ "$spp" -lt 1000000 ] || fail "SIG$sig: spp $spp"
    check_partial "$T/p.exr" 80 "SIG$sig" "${args[@]}"
    if [ $sig = INT ]; then expected=1; else expected=3; fi
    [ $rc = $expected ] || fail "SIG$sig: exit code $rc, expected $expected"
  done ;;
stop_continue)
  # Ctrl-Z / fg (SIGTSTP, SIGCONT to mpirun, which stops and continues every rank): the render goes on.
  args=(--set camera.width=96 --set camera.height=80 --threads 1)
  : >"$T/err"
  mpi_bg 2 render "$SCENE" "${args[@]}" --spp 3000 -o "$T/c.exr" >"$T/out" 2>"$T/err"
  wait_for_progress
  kill -TSTP $pid
  for i in $(seq 1 300); do  # until both ranks are stopped
    [ "$(ps -o stat= --ppid $pid | grep -c '^T')" = 2 ] && break; sleep 0.1
  done
  [ "$(ps -o stat= --ppid $pid | grep -c '^T')" = 2 ] || { kill -KILL $pid; fail "the ranks were not stopped"; }
  sleep 2
  kill -CONT $pid
  mpi_wait
  echo "stopped and continued: mpirun exit code $rc; $(cat "$T/out")"
  [ $rc = 0 ] || { cat "$T/err"; fail "exit code $rc after a stop"; }
  [ "$(meta "$T/c.exr" spp)" = 3000 ] || fail "spp $(meta "$T/c.exr" spp) after a stop, expected 3000"
  [ -z "$(meta "$T/c.exr" interrupted)" ] || fail "a stop and continue interrupted the render"
  # A SIGCONT that resumes no stop is mpirun's notice that it ends the job: the ranks stop and write.
  # (Repeated if a rank's ticker was starved for over a second and took it for the end of a stop.)
  : >"$T/err"
  mpi_bg 2 render "$SCENE" "${args[@]}" --spp 1000000 --block 1 -o "$T/c.exr" >"$T/out" 2>"$T/err"
  wait_for_progress
  for i in 1 2 3 4 5; do
    kill -CONT $pid 2>/dev/null
    for j in $(seq 1 50); do grep -q "^interrupted" "$T/err" && break 2; sleep 0.1; done
  done
  mpi_wait
  echo "SIGCONT: mpirun exit code $rc; $(cat "$T/out")"
  grep -q "^interrupted (Continued" "$T/err" || { cat "$T/err"; fail "SIGCONT did not stop the render"; }
  [ $rc = 3 ] || fail "SIGCONT: exit code $rc, expected 3"
  [ "$(meta "$T/c.exr" interrupted)" = true ] || fail "SIGCONT: metadata lack interrupted=true"
  check_partial "$T/c.exr" 80 SIGCONT "${args[@]:0:4}" ;;  # the camera options
interrupt_large)
  # Ctrl-C with mpirun's default odls_base_sigkill_timeout (1 s: SIGCONT at once, SIGTERM 1 s later,
  # SIGKILL 2 s after the Ctrl-C) mid-render of a 1280x720 image: the partial image and its standard
  # error are written, valid, and no temporary is left. A stale temporary of the output (its process
  # dead) is removed when the render starts. (1280x720: written 0.13-0.79 s after the signal with two
  # CPU hogs beside the ranks, at least 2.5x inside the 2 s; 1920x1080 took up to 1.6 s so loaded.)
  unset OMPI_MCA_odls_base_sigkill_timeout
  args=(--set camera.width=1280 --set camera.height=720 --seed 7)
  dead=$(bash -c 'echo $$')
  : >"$T/big.exr.tmp-$dead-0"; : >"$T/big.stderr.exr.tmp-$dead-0"; : >"$T/err"
  mpi_bg 2 render "$SCENE" "${args[@]}" --spp 1000000 --threads 1 --block 1 -o "$T/big.exr" >"$T/out" 2>"$T/err"
  wait_for_progress
  kill -INT $pid; t0=$(date +%s.%N)
  mpi_wait
  took=$(seconds_since "$t0")
  echo "mpirun exit code $rc in $took s after the signal; $(cat "$T/out")"
  [ -f "$T/big.exr" ] || { cat "$T/err"; fail "no partial image"; }
  [ -f "$T/big.stderr.exr" ] || { cat "$T/err"; fail "no standard error image"; }
  leftover=$(ls "$T" | grep "\.tmp-")
  [ -z "$leftover" ] || fail "temporaries left: $leftover"
  grep -q "(interrupted; written [0-9.]* s after the signal)" "$T/out" || fail "no summary line"
  [ "$(meta "$T/big.exr" interrupted)" = true ] || fail "metadata lack interrupted=true"
  [ "$(meta "$T/big.exr" valid)" = 1 ] || fail "invalid pixels"
  [ "$(meta "$T/big.stderr.exr" valid)" = 1 ] || fail "invalid standard error"
  [ "$(meta "$T/big.stderr.exr" spp)" = "$(meta "$T/big.exr" spp)" ] || fail "the two images' spp differ"
  check_partial "$T/big.exr" 720 Ctrl-C "${args[@]}"
  [ $rc = 1 ] || fail "exit code $rc, expected 1" ;;
killed_rank)
  old_output
  mpi_bg 3 render "$SCENE" --spp 1000000 --threads 1 -o "$T/o.exr" >"$T/out" 2>"$T/err"
  victim=""
  for i in $(seq 1 300); do
    for p in $(pgrep -P $pid); do
      grep -qz "^OMPI_COMM_WORLD_RANK=1$" /proc/$p/environ 2>/dev/null && victim=$p
    done
    [ -n "$victim" ] && break; sleep 0.1
  done
  [ -n "$victim" ] || { kill -KILL $pid; fail "rank 1 not found"; }
  sleep 3
  kill -KILL "$victim"; t0=$(date +%s.%N)
  mpi_wait
  took=$(seconds_since "$t0")
  echo "rank 1 killed: mpirun exit code $rc in $took s"; tail -5 "$T/err"
  [ $rc -ne 0 ] || fail "the job succeeded without a rank"
  awk -v t="$took" 'BEGIN { exit !(t < 60) }' || fail "the job took $took s to end after the kill"
  check_untouched "killed rank" ;;
reference)
  mpi 2 render "$SCENE" "${SMALL[@]}" --reference --spp 64 --threads 1 -o "$T/ref.exr" >/dev/null || fail "mpirun"
  "$COMPARE" --info "$T/ref.exr" | grep -q "^reference=rendered .* on 2 MPI ranks" || fail "metadata lack the ranks"
  [ -n "$(meta "$T/ref.exr" sceneHash)" ] || fail "no sceneHash"
  timeout 120 "$PENUMBRA" converge "$SCENE" "${SMALL[@]}" --spp 4 --strategies area --reference "$T/ref.exr" \
    -o "$T/conv" >"$T/out" 2>&1 || { cat "$T/out"; fail "converge"; }
  grep -q "reference: $T/ref.exr (with standard error)" "$T/out" || { cat "$T/out"; fail "converge did not use it"; } ;;
scene_error)
  old_output
  fault_run "missing scene on rank 2" -np 2 "$PMPI" render "$SCENE" "${LONG[@]}" : -np 1 "$PMPI" render "$T/missing.xml" "${LONG[@]}"
  expect_refusal "missing scene on rank 2" "error (rank 2 of 3): "
  grep -q "^error: rank 2 failed before the render; no rank rendered and nothing was written" "$T/err" ||
    { cat "$T/err"; fail "no summary line"; }
  # Only rank 0 writes, and it checks before rendering that it can.
  fault_run "unwritable output" -np 2 "$PMPI" render "$SCENE" "${LONG[@]:0:8}" -o "$T/no-such-dir/o.exr"
  expect_refusal "unwritable output" "error (rank 0 of 2): " ;;
disagreement)
  # Rank 0 renders SMALL at 8 spp in blocks of 4; the other ranks differ in one thing each.
  base=(--threads 1 -o "$T/o.exr" "${SMALL[@]}")
  r0=(render "$SCENE" "${base[@]}" --spp 8 --block 4)
  old_output
  fault_run "image size" -np 1 "$PMPI" "${r0[@]}" : -np 1 "$PMPI" "${r0[@]}" --set camera.width=32
  expect_refusal "image size" "error: rank 1 disagrees with rank 0 on camera.width: 32 vs 48"
  # One job of 9 ranks: each differing rank is named with its first difference; rank 8 renders the
  # same scene from a copy under another path and agrees, rank 7 a copy whose OBJ file differs.
  for d in a b; do mkdir -p "$T/$d"; cp "$SCENE" "$(dirname "$SCENE")/plane.obj" "$T/$d/"; done
  sed -i 's/^v 1 0 -1$/v 1 0.5 -1/' "$T/b/plane.obj"
  differing=(-np 1 "$PMPI" "${r0[@]}"
    : -np 1 "$PMPI" render "$SCENE" "${base[@]}" --spp 16 --block 4
    : -np 1 "$PMPI" render "$SCENE" "${base[@]}" --spp 8 --block 8
    : -np 1 "$PMPI" "${r0[@]}" --seed 3
    : -np 1 "$PMPI" "${r0[@]}" --set sampler.type=stratified
    : -np 1 "$PMPI" "${r0[@]}" --set emitter.radiance=1,1,1
    : -np 1 "$PMPI" "${r0[@]}" --set integrator.measure=solid-angle
    : -np 1 "$PMPI" render "$T/b/sphere-area.xml" "${base[@]}" --spp 8 --block 4
    : -np 1 "$PMPI" render "$T/a/sphere-area.xml" "${base[@]}" --spp 8 --block 4)
  old_output
  fault_run "ranks 1-7 differ" "${differing[@]}"
  expect_refusal "spp" "error: rank 1 disagrees with rank 0 on spp: 16 vs 8"
  expect_refusal "block" "error: rank 2 disagrees with rank 0 on block: 8 vs 4"
  expect_refusal "seed" "error: rank 3 disagrees with rank 0 on seed: 3 vs 0"
  expect_refusal "sampler" "error: rank 4 disagrees with rank 0 on sampler.type: stratified vs independent"
  expect_refusal "emitter radiance" \
    "error: rank 5 disagrees with rank 0: the resolved scene differs at emitter.radiance ($SCENE:18): 1, 1, 1 vs 300, 300, 300"
  expect_refusal "integrator" "error: rank 6 disagrees with rank 0 on integrator.measure: solid-angle vs area"
  expect_refusal "OBJ file" \
    "error: rank 7 disagrees with rank 0: the resolved scene differs at shape#3.filename (contents) ($SCENE:31, $(dirname "$SCENE")/plane.obj): fnv1a64 "
  [ "$(grep -c "disagree" "$T/err")" = 7 ] || { cat "$T/err"; fail "ranks 1-7 differ: not exactly 7 ranks named"; } ;;
argument_error)
  old_output
  fault_run "bad argument on rank 1" -np 1 "$PMPI" render "$SCENE" "${LONG[@]}" : -np 1 "$PMPI" render "$SCENE" "${LONG[@]}" --threads 0
  expect_refusal "bad argument on rank 1" "error (rank 1 of 2): --threads: Value 0 not in range"
  fault_run "bad argument on rank 0" -np 1 "$PMPI" render "$SCENE" "${LONG[@]}" --threads 0 : -np 1 "$PMPI" render "$SCENE" "${LONG[@]}"
  expect_refusal "bad argument on rank 0" "error (rank 0 of 2): --threads: Value 0 not in range"
  fault_run "bad argument on every rank" -np 2 "$PMPI" render "$SCENE" "${LONG[@]}" --block 3
  expect_refusal "bad argument on every rank" "error (ranks 0-1 of 2): --block must be a power of two, not 3"
  fault_run "--help on rank 1 only" -np 1 "$PMPI" render "$SCENE" "${LONG[@]}" : -np 1 "$PMPI" render --help
  expect_refusal "--help on rank 1 only" "error (rank 1 of 2): --help given, but not to every rank"
  # Seeds: any 64-bit unsigned integer is taken as given, one beyond is refused as the CLI refuses it.
  fault_run "seed beyond 64 bits" -np 2 "$PMPI" render "$SCENE" "${LONG[@]}" --seed 18446744073709551616
  expect_refusal "seed beyond 64 bits" \
    "error (ranks 0-1 of 2): --seed: '18446744073709551616' is out of range (at most 18446744073709551615)"
  mpi 2 render "$SCENE" "${SMALL[@]}" --spp 4 --threads 1 --seed 18446744073709551615 -o "$T/s.exr" >/dev/null ||
    fail "--seed 18446744073709551615: mpirun"
  [ "$(meta "$T/s.exr" seed)" = 18446744073709551615 ] ||
    fail "--seed 18446744073709551615: metadata say seed=$(meta "$T/s.exr" seed)"
  echo "--seed 18446744073709551615: rendered with seed=$(meta "$T/s.exr" seed)" ;;
write_error)
  # A failure on a rank after the agreement: rank 0's write fails because the output's directory was
  # replaced by a file during the render (the old output moved away with it); the job ends with
  # MPI_Abort, exit 2, the error printed once with its rank, and the old output is not touched.
  mkdir "$T/d"; printf 'old image' >"$T/d/o.exr"; printf 'old standard error' >"$T/d/o.stderr.exr"
  sums=$(cd "$T/d" && sha256sum o.exr o.stderr.exr)
  : >"$T/err"
  mpi_bg 2 render "$SCENE" "${LONG[@]:0:8}" -o "$T/d/o.exr" >"$T/out" 2>"$T/err"
  wait_for_progress
  mv "$T/d" "$T/moved" && : >"$T/d" || { kill -KILL $pid; fail "could not replace the output's directory"; }
  kill -USR1 $pid; t0=$(date +%s.%N)  # rank 0 writes what the ranks have rendered: into a file, not a directory
  mpi_wait
  took=$(seconds_since "$t0")
  [ $rc = 2 ] || { cat "$T/err"; fail "write error: exit code $rc, expected 2"; }
  n=$(grep -c "^error (rank 0 of 2): .*$T/d/o.exr" "$T/err")
  [ "$n" = 1 ] || { cat "$T/err"; fail "write error: rank 0's error printed $n times, expected once"; }
  [ "$(cd "$T/moved" && sha256sum o.exr o.stderr.exr 2>&1)" = "$sums" ] || fail "write error: the old output changed"
  ! ls "$T/moved" | grep -q "tmp-" || fail "write error: a temporary was left: $(ls "$T/moved")"
  [ "$(cat "$T/d")" = "" ] || fail "write error: the file in the directory's place was written"
  for i in $(seq 20); do pgrep -f "$T/d/o.exr" >/dev/null || break; sleep 0.1; done
  ! pgrep -f "$T/d/o.exr" >/dev/null || { pkill -KILL -f "$T/d/o.exr"; fail "write error: a rank outlived mpirun"; }
  echo "write error: exit 2 in $took s after the signal: $(grep "^error (rank 0" "$T/err")" ;;
start_failure)
  old_output
  fault_run "missing program" -np 1 "$PMPI" render "$SCENE" "${LONG[@]}" : -np 1 "$T/no-such-program"
  [ $rc != 0 ] || { cat "$T/err"; fail "missing program: exit code 0"; }
  grep -q "could not access" "$T/err" || { cat "$T/err"; fail "missing program: no message from mpirun"; }
  check_untouched "missing program"
  echo "missing program: mpirun exit code $rc in $took s"
  fault_run "failing program" -np 1 "$PMPI" render "$SCENE" "${LONG[@]}" : -np 1 false
  [ $rc = 1 ] || { cat "$T/err"; fail "failing program: exit code $rc, expected 1 (false's)"; }
  check_untouched "failing program"
  echo "failing program: mpirun exit code $rc in $took s"
  # A process of the job that exits with 0 without starting MPI. When it exits after another rank has
  # called MPI_Init, mpirun ends the job itself (exit code 1, "exiting improperly"); when before, as
  # here (rank 0 starts 2 s late), MPI_Init waits for it for ever and the start-up watchdog ends it.
  export PENUMBRA_MPI_START_TIMEOUT=2
  fault_run "quiet program" -np 1 sh -c 'sleep 2; exec "$0" "$@"' "$PMPI" render "$SCENE" "${LONG[@]}" : -np 1 true
  unset PENUMBRA_MPI_START_TIMEOUT
  if [ $rc = 1 ] && grep -q "exiting improperly" "$T/err"; then  # `true` was late after all
    check_untouched "quiet program"
    echo "quiet program: ended by mpirun (exit code 1) in $took s"
  else
    expect_refusal "quiet program" "error (rank 0): the MPI job did not start within 2 s"
  fi
  # Ctrl-C while a rank has not started (rank 0 waits in MPI_Init): mpirun ends the job, exit code 1.
  nap=100.$$  # a sleep of its own, told apart from any other process
  "$MPIRUN" --allow-run-as-root --oversubscribe -np 1 "$PMPI" render "$SCENE" "${LONG[@]}" : -np 1 sleep $nap \
    >"$T/err" 2>&1 & pid=$!
  (sleep 240 & echo $! >"$T/watchdog"; wait $! && kill -KILL $pid) >/dev/null 2>&1 &
  for i in $(seq 100); do pgrep -f "$T/o.exr" >/dev/null && break; sleep 0.1; done
  sleep 1
  kill -INT $pid; t0=$(date +%s.%N)
  mpi_wait
  took=$(seconds_since "$t0")
  [ $rc = 1 ] || { cat "$T/err"; fail "Ctrl-C before the render: exit code $rc, expected 1"; }
  pgrep -fx "sleep $nap" >/dev/null && { pkill -fx "sleep $nap"; fail "Ctrl-C before the render: a rank outlived mpirun"; }
  check_untouched "Ctrl-C before the render"
  echo "Ctrl-C before the render: mpirun exit code $rc in $took s after the signal" ;;
*) fail "unknown case $case_" ;;
esac
echo PASS
