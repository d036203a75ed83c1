#!/usr/bin/env bash
# `make demo`: the main job end to end on the embedded default (see README.md).
# server -> user -> record synthetic clip -> publish -> browse nearby -> play headless -> stop.
# Environment: REENACT_DEMO_PORT (default 0 = any free port), REENACT_DEMO_FRAMES (frames to
# record, default: the whole scenario), REENACT_DEMO_SCENARIO (default turn-and-kick),
# REENACT_DEMO_WORK (server database, clip, cache; default var/demo), REENACT_DEMO_OUT
# (rendered outputs; default demo-out).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD_DIR=${1:-build}
case "$BUILD_DIR" in /*) ;; *) BUILD_DIR="$ROOT/$BUILD_DIR" ;; esac
BIN_SERVER="$BUILD_DIR/server/reenact-server"
BIN_CAPTURE="$BUILD_DIR/capture-client/reenact-capture"
BIN_VIEWER="$BUILD_DIR/viewer-client/reenact-viewer"
PORT=${REENACT_DEMO_PORT:-0}
SCENARIO=${REENACT_DEMO_SCENARIO:-turn-and-kick}
WORK=${REENACT_DEMO_WORK:-$ROOT/var/demo}
OUT=${REENACT_DEMO_OUT:-$ROOT/demo-out}
LAT=48.137154
LON=11.576124

fail() { echo "demo: $*" >&2; exit 1; }
for b in "$BIN_SERVER" "$BIN_CAPTURE" "$BIN_VIEWER"; do
  [ -x "$b" ] || fail "missing $b; run 'make demo' (it builds first)"
done

rm -rf "$WORK" "$OUT"
mkdir -p "$WORK" "$OUT"
START=$(date +%s)

echo "== 1. start reenact-server (fresh database $WORK/reenact.db)"
"$BIN_SERVER" serve --db "$WORK/reenact.db" --listen "127.0.0.1:$PORT" \
  >"$WORK/server.out" 2>"$WORK/server.err" &
SERVER_PID=$!
stop_server() {
  if kill -0 "$SERVER_PID" 2>/dev/null; then
    kill -TERM "$SERVER_PID" 2>/dev/null || true
    wait "$SERVER_PID" 2>/dev/null || true
  fi
}
trap stop_server EXIT
URL=""
for _ in $(seq 1 100); do
  URL=$(sed -n 's/^listening on \(http:[^ ]*\).*/\1/p' "$WORK/server.out" | head -n 1)
  [ -n "$URL" ] && break
  kill -0 "$SERVER_PID" 2>/dev/null || break
  sleep 0.1
done
if [ -z "$URL" ]; then
  msg=$(tail -n 1 "$WORK/server.err" 2>/dev/null)
  fail "reenact-server did not start: ${msg:-no output within 10 s}"
fi
echo "   listening on $URL"

echo "== 2. create a user"
TOKEN=$("$BIN_SERVER" user add demo --db "$WORK/reenact.db" 2>/dev/null | head -n 1)
[ -n "$TOKEN" ] || fail "reenact-server user add printed no token"
echo "   user 'demo', token ${TOKEN:0:6}..."

echo "== 3. record synthetic:$SCENARIO"
FRAMES_FLAG=()
[ -n "${REENACT_DEMO_FRAMES:-}" ] && FRAMES_FLAG=(--frames "$REENACT_DEMO_FRAMES")
"$BIN_CAPTURE" record --source "synthetic:$SCENARIO" --out "$WORK/clip" "${FRAMES_FLAG[@]}" \
  --title "Turn and kick (demo)" --author demo | sed 's/^/   /'

echo "== 4. publish at $LAT,$LON"
PUBLISH=$("$BIN_CAPTURE" publish "$WORK/clip" --server "$URL" --token "$TOKEN" --lat "$LAT" --lon "$LON")
echo "$PUBLISH" | grep -v '^clip_id=' | sed 's/^/   /'
CLIP_ID=$(echo "$PUBLISH" | sed -n 's/^clip_id=//p')
[ -n "$CLIP_ID" ] || fail "publish printed no clip id"

echo "== 5. browse clips near $LAT,$LON"
"$BIN_VIEWER" browse --server "$URL" --near "$LAT,$LON" --radius-m 500 | sed 's/^/   /'

echo "== 6. play $CLIP_ID headless from 60 degrees around the subject"
PLAY=$("$BIN_VIEWER" play "$CLIP_ID" --server "$URL" --camera orbit --orbit-deg 60 \
  --headless --out "$OUT" --cache "$WORK/cache")
echo "$PLAY" | sed 's/^/   /'

echo "== 7. stop the server"
stop_server
trap - EXIT
END=$(date +%s)

FRAMES=$(ls "$OUT"/frames/frame_*.png | wc -l)
CLIP_BYTES=$(du -sb "$WORK/clip/frames" | cut -f1)
echo
echo "demo done in $((END - START)) s"
echo "  frames rendered : $FRAMES"
echo "  bytes per frame : $((CLIP_BYTES / $(ls "$WORK"/clip/frames | wc -l))) (stored clip)"
echo "  render fps      : $(echo "$PLAY" | sed -n 's/.*render \([0-9.]*\) fps.*/\1/p')"
echo "  outputs         : $OUT/frames/, $OUT/contact_sheet.png, $OUT/reenactment.mp4, $OUT/render.json"
