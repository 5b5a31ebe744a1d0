#!/bin/sh
# Runs a command on a 1 MiB stack, then prints its exit status: a stack
# overflow (128 + SIGSEGV) cannot pass for the expected "exit status 0".
ulimit -s 1024
"$@"
echo "exit status $?"
