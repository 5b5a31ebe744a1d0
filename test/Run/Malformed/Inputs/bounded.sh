#!/bin/sh
# Runs a command under a 4 GB address-space limit and a 120 s time limit,
# then prints its exit status: a crash (128 + signal), a time-out (124) or
# running out of memory cannot pass for the expected "exit status 1".
ulimit -v 4000000
timeout 120 "$@"
echo "exit status $?"
