#!/usr/bin/env bash
# `mimic play` as a user runs it (control/play_session, app/play_command):
#  1. headless, from a script: a key requests the run, it takes over, a push and a cube are
#     thrown, and the events and the video are written; bad scripts and options are named errors;
#  2. the real window under a virtual X server (Xvfb): a key pressed on it (xdotool) requests the
#     run, which takes over; the screenshot is a picture of the scene, not an empty frame.
# The committed walk and run act on the humanoid of ../shared/data. Skips (77) what this machine
# cannot run: the shared data, or Xvfb and xdotool for the window (scripts/setup.sh installs them).
# Usage: play_test.sh MIMIC SOURCE_DIR OUT_DIR
set -euo pipefail
mimic=$1 src=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
fail() { echo "FAIL: $*" >&2; exit 1; }
data=${MIMIC_DATA:-$src/../shared/data}
[ -f "$data/deepmimic/characters/humanoid3d.txt" ] || { echo "SKIP: no humanoid at $data (../shared/data)"; exit 77; }
walk=$src/models/humanoid_walk_iccgan run=$src/models/humanoid_run_iccgan_straight_loop
# tau -1: every state allows a request, so the take-over is the step after the key.
play() { "$mimic" play "$walk" "$run" --tau -1 --width 320 --height 180 "$@"; }

# 1. Headless.
cat > "$out/session.txt" <<'SCRIPT'
# seconds key
0.3 2   # the run
0.6 p   # a push
0.8 b   # a cube
SCRIPT
play --headless --script "$out/session.txt" --seconds 1.2 -o "$out/session.mp4" --json "$out/events.json" --motion "$out/session.mclip" > "$out/headless.log" 2>&1 ||
  { cat "$out/headless.log"; fail "mimic play --headless"; }
events=$(tr -d ' \n' < "$out/events.json")
for want in '{"t":0.3,"event":"request","skill":"humanoid_run_iccgan_straight_loop"}' \
            '{"t":0.3333,"event":"switch","skill":"humanoid_run_iccgan_straight_loop"}' \
            '{"t":0.6,"event":"push","skill":"humanoid_run_iccgan_straight_loop"}' \
            '{"t":0.8,"event":"cube","skill":"humanoid_run_iccgan_straight_loop"}'; do
  [[ $events == *"$want"* ]] || fail "events.json lacks $want: $events"
done
[[ $events == '[{"t":0,"event":"reset"'* ]] && fail "the session's own start is not an event: $events"
[ -s "$out/session.mp4" ] || fail "no video"
grep -q "wrote $out/session.mp4 (36 frames)" "$out/headless.log" || { cat "$out/headless.log"; fail "1.2 s at 30 Hz is 36 frames"; }
# The character's motion: the start and 36 steps at the control rate, walking then running on.
"$mimic" motion info "$out/session.mclip" > "$out/motion.txt" 2>&1 || { cat "$out/motion.txt"; fail "the session's motion is no clip"; }
grep -q "frames      37 at 30.000 Hz = 1.200 s" "$out/motion.txt" || { cat "$out/motion.txt"; fail "the motion is not the start and 36 steps at 30 Hz"; }
travel=$(awk '/^travel/ {print $2}' "$out/motion.txt")
awk -v t="$travel" 'BEGIN {exit !(t > 1.0)}' || fail "the motion travels $travel m in 1.2 s of walking and running (more than 1 m expected)"

# A model whose environment has no character (the planar walker): no cubes to set up for it, and
# the video runs at its own control rate from the first frame (125 Hz: 0.2 s is 25 frames).
"$mimic" play "$src/models/walker_ppo" --headless --seconds 0.2 --width 320 --height 180 -o "$out/walker.mp4" > "$out/walker.log" 2>&1 ||
  { cat "$out/walker.log"; fail "mimic play of the planar walker"; }
grep -q "wrote $out/walker.mp4 (25 frames)" "$out/walker.log" || { cat "$out/walker.log"; fail "0.2 s of the walker at 125 Hz is 25 frames"; }

# The reaching arm is seen by its environment's own camera, from above: its pale table fills the
# picture (from the side camera that follows a character, the table is a speck on black).
"$mimic" play "$src/models/reacher_ppo" --headless --seconds 0.2 --width 320 --height 180 -o "$out/reacher.mp4" > "$out/reacher.log" 2>&1 ||
  { cat "$out/reacher.log"; fail "mimic play of the reacher"; }
brightness=$(ffmpeg -loglevel error -i "$out/reacher.mp4" -vf "select=eq(n\,5),signalstats,metadata=print:key=lavfi.signalstats.YAVG:file=-" -f null - |
  awk -F= '/YAVG/ {print $2}')
awk -v b="$brightness" 'BEGIN {exit !(b > 100)}' || fail "the reacher's frame has mean brightness '$brightness' (its table, seen from above, should fill it: > 100)"

# DeepMimic's dog (its committed trot): a body without a chest gets its cubes at its root.
printf '0.3 b\n' > "$out/dog.txt"
"$mimic" play "$src/models/dog_trot_tracking_drift" --headless --script "$out/dog.txt" --seconds 0.6 --json "$out/dog.json" > "$out/dog.log" 2>&1 ||
  { cat "$out/dog.log"; fail "mimic play of the dog's trot"; }
events=$(tr -d ' \n' < "$out/dog.json")
[[ $events == *'{"t":0.3,"event":"cube","skill":"dog_trot_tracking_drift"}'* ]] || fail "no cube thrown at the dog: $events"

# Skills in runs' model directories (what mimic imitate writes: RUN/model) are named by their runs.
mkdir -p "$out/my_walk" "$out/my_run"
ln -s "$walk" "$out/my_walk/model" && ln -s "$run" "$out/my_run/model"
printf '0.1 2\n' > "$out/runs.txt"
"$mimic" play "$out/my_walk/model" "$out/my_run/model" --tau -1 --headless --script "$out/runs.txt" --seconds 0.3 --json "$out/runs.json" \
  > "$out/runs.log" 2>&1 || { cat "$out/runs.log"; fail "mimic play RUN/model RUN/model"; }
events=$(tr -d ' \n' < "$out/runs.json")
[[ $events == *'{"t":0.1,"event":"request","skill":"my_run"}'* ]] || fail "RUN/model is not named by its run: $events"

# A script's times count the frames shown, paused ones too: paused from 0.2 s to 0.5 s, the
# request at 0.6 s comes after 0.3 s of the session.
printf '0.2 space\n0.5 space\n0.6 2\n' > "$out/paused.txt"
play --headless --script "$out/paused.txt" --seconds 0.8 --json "$out/paused.json" > "$out/paused.log" 2>&1 || { cat "$out/paused.log"; fail "a paused session"; }
events=$(tr -d ' \n' < "$out/paused.json")
[[ $events == *'{"t":0.3,"event":"request","skill":"humanoid_run_iccgan_straight_loop"}'* ]] || fail "paused 0.3 s, the request at 0.6 s is not at 0.3 s of the session: $events"

# Named errors, nothing written.
bad() {  # expected message, then the arguments
  local want=$1; shift
  if "$mimic" play "$walk" "$@" > "$out/bad.log" 2>&1; then fail "mimic play $* succeeded"; fi
  grep -qF -- "$want" "$out/bad.log" || { cat "$out/bad.log"; fail "mimic play $*: no '$want'"; }
}
printf '0.5 2\n1.0 x\n' > "$out/unknown_key.txt"
bad "unknown_key.txt:2: unknown key 'x'" --headless --script "$out/unknown_key.txt" --json "$out/never.json"
printf '1.0 2\n0.5 1\n' > "$out/backwards.txt"
bad "backwards.txt:2: the times must not go back" --headless --script "$out/backwards.txt" --json "$out/never.json"
printf 'soon 2\n' > "$out/bad_time.txt"
bad "bad_time.txt:1: 'soon' is not a time in seconds" --headless --script "$out/bad_time.txt" --json "$out/never.json"
bad "give -o (a video), --json (the events) or --motion" --headless --seconds 1
bad "give --seconds, or a --script" --headless --json "$out/never.json"
bad "the character's motion is written as an .mclip" --headless --seconds 1 --motion "$out/never.bvh"
[ ! -e "$out/never.bvh" ] || fail "a refused --motion was written"
bad "two skills are named 'humanoid_walk_iccgan'" --recover "$walk/" --headless --seconds 1 --json "$out/never.json"
[ ! -e "$out/never.json" ] || fail "a failed play wrote its events"
(unset DISPLAY; bad "DISPLAY is not set: run with --headless, or under xvfb-run" --seconds 1)

# The transition test's rules and its curves (mimic eval --transitions, mimic plot): one trial a
# rule, tau 1.01 (above any score or pose-matching readiness: nothing is granted by those).
"$mimic" eval "$walk" --episodes 1 --trials 1 --transitions "$run" --transition-trials 1 --transition-taus 1.01 \
  --transition-rules score,matching,immediately --json "$out/transitions.json" > "$out/transitions.log" 2>&1 ||
  { cat "$out/transitions.log"; fail "mimic eval --transitions"; }
cells=$(tr -d ' \n' < "$out/transitions.json")
for rule in score matching; do
  [[ $cells == *"\"rule\":\"$rule\",\"threshold\":1.01,\"trials\":1,\"switched\":0"* ]] || fail "the $rule rule at tau 1.01 granted a request: $cells"
done
[[ $cells == *'"rule":"immediately","threshold":0,"trials":1,"switched":1'* ]] || fail "switching at once did not switch: $cells"
[[ $cells == *'"rule":"value"'* ]] && fail "--transition-rules left out the value rule, but it ran: $cells"
"$mimic" plot "$out/transitions.json" -o "$out/transitions.svg" > "$out/plot.log" 2>&1 || { cat "$out/plot.log"; fail "mimic plot of transitions"; }
for label in "by score" "by matching" "at once" "threshold tau" "switch success"; do
  grep -q "$label" "$out/transitions.svg" || fail "the transition chart has no '$label'"
done
"$mimic" plot "$out/transitions.json" --y wait -o "$out/waits.svg" > "$out/plot.log" 2>&1 || { cat "$out/plot.log"; fail "mimic plot --y wait"; }
grep -q "mean wait" "$out/waits.svg" || fail "the wait chart has no 'mean wait'"
if "$mimic" eval "$walk" --transitions "$run" --transition-rules nearest > "$out/bad.log" 2>&1; then fail "an unknown rule was taken"; fi
grep -q "nearest not in" "$out/bad.log" || { cat "$out/bad.log"; fail "--transition-rules nearest: no error naming it"; }

# Robustness with recovery (mimic eval --recover, mimic plot --y performing): without cubes the
# walk performs throughout, with the run as a stand-in get-up or not; without masses, a named error.
"$mimic" eval "$walk" --episodes 1 --trials 1 --robustness 0 --robustness-trials 1 --robustness-seconds 0.5 --recover "$run" \
  --json "$out/recovery.json" > "$out/recovery.log" 2>&1 || { cat "$out/recovery.log"; fail "mimic eval --recover"; }
recovery=$(tr -d ' \n' < "$out/recovery.json")
[[ $recovery == *'"recovery":{"seconds":0.5,"trials":1,"tau":-1,'* ]] || fail "no recovery figures: $recovery"
[[ $recovery == *'{"mass":0,"without":{"performing_mean":1,"performing_std":0,"downs_mean":0},"with":{"performing_mean":1,'* ]] ||
  fail "the calm walk did not perform throughout: $recovery"
"$mimic" plot "$out/recovery.json" --y performing -o "$out/recovery.svg" > "$out/plot.log" 2>&1 || { cat "$out/plot.log"; fail "mimic plot --y performing"; }
grep -q "with recovery" "$out/recovery.svg" || fail "the recovery chart has no 'with recovery' line"
if "$mimic" eval "$walk" --episodes 1 --recover "$run" > "$out/bad.log" 2>&1; then fail "--recover without --robustness was taken"; fi
grep -q "give the cube masses with --robustness" "$out/bad.log" || { cat "$out/bad.log"; fail "--recover without masses: no error naming it"; }

# 2. The window under Xvfb, a key pressed on it.
if ! command -v xvfb-run > /dev/null || ! command -v xdotool > /dev/null; then
  echo "SKIP: the window test needs xvfb-run and xdotool (scripts/setup.sh installs them)"; exit 77
fi
cat > "$out/window.sh" <<WINDOW
set -euo pipefail
"$mimic" play "$walk" "$run" --tau -1 --width 320 --height 180 --seconds 3 --screenshot "$out/shot.ppm" --json "$out/window.json" &
pid=\$!
# Polled rather than 'xdotool search --sync': a search dies on an X error (BadWindow) when a window
# it lists is gone before it reads it, as the short-lived windows of GL's start-up are.
win=
for _ in \$(seq 600); do
  win=\$(xdotool search --onlyvisible --name "mimic play" 2> /dev/null | head -1) || true
  [ -n "\$win" ] && break
  sleep 0.1
done
[ -n "\$win" ] || { echo "no 'mimic play' window within 60 s"; exit 1; }
xdotool windowfocus --sync "\$win" key 2
wait \$pid
WINDOW
# Under the sanitizers, no leak check for the window: Mesa's GLX driver, loaded and unloaded by
# the GL dispatch library, keeps allocations whose stacks LeakSanitizer cannot name once it is
# unloaded (so no suppression can match them); the same session without a window is leak-checked
# above.
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
  timeout 600 xvfb-run -a -s "-screen 0 640x480x24" bash "$out/window.sh" > "$out/window.log" 2>&1 || { cat "$out/window.log"; fail "mimic play in a window under Xvfb"; }
events=$(tr -d ' \n' < "$out/window.json")
[[ $events == *'"event":"request","skill":"humanoid_run_iccgan_straight_loop"'* ]] || fail "the key 2 pressed on the window requested nothing: $events"
[[ $events == *'"event":"switch","skill":"humanoid_run_iccgan_straight_loop"'* ]] || fail "the run did not take over: $events"
# The screenshot: a 320x180 PPM, and a picture (the floor, the sky, the character, the text: many
# colours), not an empty or one-colour frame.
[ "$(head -c 15 "$out/shot.ppm" | tr '\n' ' ')" = "P6 320 180 255 " ] || fail "the screenshot is not a 320x180 PPM"
[ "$(stat -c %s "$out/shot.ppm")" -eq $((15 + 320 * 180 * 3)) ] || fail "the screenshot's size is not 320x180x3 bytes after its header"
colours=$(tail -c $((320 * 180 * 3)) "$out/shot.ppm" | od -An -v -tu1 -w3 | sort -u | wc -l)
[ "$colours" -gt 200 ] || fail "the screenshot has $colours colours: not a picture of the scene"
echo "play: headless and window sessions as expected ($colours colours in the window's frame)"
