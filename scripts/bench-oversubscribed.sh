#!/usr/bin/env bash
# Two runs at once: what a threaded step loses when the machine has more stepping threads
# than cores (a test harness running two simulation tests side by side, or a user starting
# two commands). Runs the DESIGN §8 pour (2 000 spheres) twice at once with --threads 2
# each, then twice at once with --threads 1 each (the same work without oversubscription),
# and prints one JSON line per round:
#
#   {"round":1,"two_threads_each_s":[a,b],"one_thread_each_s":[a,b],"ratio":…,"load_average":…}
#
# ratio = the slower of the 2-thread pair over the slower of the 1-thread pair: 1 means the
# threaded step costs nothing extra when oversubscribed.
#
# Usage: scripts/bench-oversubscribed.sh [--steps N] [--rounds N] [--binary PATH]
set -euo pipefail
cd "$(dirname "$0")/.."

steps=10000
rounds=3
binary=target/release/arachis
while [ $# -gt 0 ]; do
    case "$1" in
        --steps) steps="$2"; shift 2 ;;
        --rounds) rounds="$2"; shift 2 ;;
        --binary) binary="$2"; shift 2 ;;
        *) echo "bench-oversubscribed.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done
if [ "$binary" = target/release/arachis ]; then
    cargo build --release -q -p arachis
fi

# Wall milliseconds of two pours at once with $1 threads each, as "a b".
pair() {
    local dir
    dir=$(mktemp -d)
    for k in a b; do
        ( s=$(date +%s%N); "$binary" pour --particles 2000 --steps "$steps" --threads "$1" >/dev/null
          e=$(date +%s%N); echo $(( (e - s) / 1000000 )) > "$dir/$k" ) &
    done
    wait
    echo "$(cat "$dir/a") $(cat "$dir/b")"
    rm -rf "$dir"
}

for round in $(seq 1 "$rounds"); do
    read -r t2a t2b <<< "$(pair 2)"
    read -r t1a t1b <<< "$(pair 1)"
    load=$(cut -d' ' -f1 /proc/loadavg)
    awk -v r="$round" -v a="$t2a" -v b="$t2b" -v c="$t1a" -v d="$t1b" -v l="$load" 'BEGIN {
        a /= 1000; b /= 1000; c /= 1000; d /= 1000;
        m2 = (a > b) ? a : b; m1 = (c > d) ? c : d;
        printf "{\"round\":%d,\"two_threads_each_s\":[%.2f,%.2f],\"one_thread_each_s\":[%.2f,%.2f],\"ratio\":%.3f,\"load_average\":%s}\n", r, a, b, c, d, m2 / m1, l
    }'
done
