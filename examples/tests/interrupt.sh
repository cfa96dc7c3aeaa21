#!/bin/sh
# interrupt.sh SIGNAL TRACE: starts a long render to interrupted.png, waits until its
# temporary file "interrupted.png.partial-*" exists (so the temporary name is not the
# target), sends SIGNAL, and checks what is left: after TERM no file at all; after
# KILL (which no program can catch) no interrupted.png, a leftover temporary file is
# allowed and removed here. Run twice: once without interrupted.png, once with an
# existing one, which must keep its bytes. (Not INT: a shell starts background jobs with
# SIGINT ignored, and output_file leaves an ignored signal ignored.)
set -u
signal=$1
trace=$2
for existing in no yes; do
    rm -f interrupted.png interrupted.png.partial-*
    if [ "$existing" = yes ]; then printf 'old bytes\n' > interrupted.png; fi
    "$trace" --scene gallery --width 320 --height 180 --spp 65536 --quiet --out interrupted.png &
    pid=$!
    waited=0
    while ! ls interrupted.png.partial-* >/dev/null 2>&1; do
        sleep 0.05
        waited=$((waited + 1))
        if [ $waited -gt 200 ]; then echo "no temporary file after 10 s"; kill -KILL $pid; exit 1; fi
    done
    sleep 0.2
    kill -"$signal" $pid
    wait $pid
    status=$?
    if [ $status -eq 0 ]; then echo "the render finished before SIG$signal"; exit 1; fi
    if [ "$existing" = yes ]; then
        if [ "$(cat interrupted.png)" != "old bytes" ]; then echo "SIG$signal changed the existing file"; exit 1; fi
    elif [ -e interrupted.png ]; then
        echo "SIG$signal left interrupted.png"; exit 1
    fi
    if [ "$signal" != KILL ] && ls interrupted.png.partial-* >/dev/null 2>&1; then
        echo "SIG$signal left a temporary file: $(ls interrupted.png.partial-*)"; exit 1
    fi
    rm -f interrupted.png interrupted.png.partial-*
done
echo "SIG$signal: target untouched"
