#!/bin/bash
# usage: run_copy.sh <template case> <tfdemFoam binary>: a fresh copy of the template run to its end
set -e
d=$(mktemp -d); cp -r $1/. $d/
cd $d && $2 > log 2>&1; grep "TFDEM hard spheres" log; grep "^ExecutionTime" log | tail -1; cd / && rm -rf $d
