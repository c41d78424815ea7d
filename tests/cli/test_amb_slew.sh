#!/usr/bin/env bash
# The amplifier's slew-rate limit through the case key ambs[].slew_rate and the tool. A rigid rotor
# (one lumped-mass element) falls freely under gravity with its AMB off (no force: ks = kp = 0),
# while the amplifier follows the derivative command ki kd g t through its lag tau: the lag's rate
# ki kd g (1 - e^{-t/tau}) reaches the limit ki S (S < kd g) at t* = -tau ln(1 - S/(kd g)) and the
# amplifier slews from then on, so the run's time_slewing is end_time - t* (the root instant against
# its closed form; tests/validation/test_slew.c follows Fc itself). Also: touchdown info shows the
# limit, slew_rate = 0 slews never, and a limit of 1e6 A/s is never reached (time_slewing 0).
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
work=$(mktemp -d "${PWD}/amb-slew.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

cat >"$work/fall.cfg" <<'EOF'
description = "a rigid rotor falling freely, its AMB off, the amplifier slewing";
shaft = { length = 0.2; elements = 1; outer_diameter = 0.1;
          material = { E = 2.11e11; G = 8.1e10; density = 7810.0; }; mass = "lumped"; };
ambs = ( { node = 0; ks = 0.0; ki = 200.0; kp = 0.0; kd = 40.0; bandwidth = 100.0;
           force_capacity = 1.0e6; slew_rate = 200.0; } );
schedule = ( { time = 0.0; amb_off = 0; } );
gravity = { g = 9.81; };
speed = 0.0;
start = "rest";
end_time = 0.01;
solver = { rtol = 1.0e-10; atol = 1.0e-13; };
EOF

t "$work/info" info "$work/fall.cfg"
check "info: exit 0 (got $rc: $(head -c 300 "$work/info/.err"))" test "$rc" = 0
check "info shows the limit ($(grep '^amb 0' "$work/info/.out"))" grep -q 'slew rate 200 A/s' "$work/info/.out"

t "$work/run" run -q --json "$work/fall.cfg" -o r
check "run: exit 0 (got $rc: $(head -c 300 "$work/run/.err"))" test "$rc" = 0
slewing=$(jf "$work/run/.out" time_slewing)
# t* = -tau ln(1 - S/(kd g)), tau = 1/(2 pi 100 Hz)
expected=$(awk 'BEGIN { tau = 1 / (2 * atan2(0, -1) * 100); printf "%.17g", 0.01 + tau * log(1 - 200 / (40 * 9.81)) }')
check "run: time_slewing $slewing s = end_time - t* = $expected s to 1e-9 s" \
    awk -v a="$slewing" -v b="$expected" 'BEGIN { d = a - b; exit !(a != "" && d < 1e-9 && d > -1e-9) }'
py=$(h5py_python)
h5=$([ -n "$py" ] && "$py" -c 'import sys, h5py; print(repr(float(h5py.File(sys.argv[1], "r").attrs["time_slewing"])))' \
    "$work/run/r.h5" 2>&1)
check "run: the HDF5 file's time_slewing attribute ($h5) is the summary's ($slewing)" \
    awk -v a="$slewing" -v b="$h5" 'BEGIN { exit !(b != "" && a == b + 0) }'

t "$work/none" run -q --json --set 'ambs[0].slew_rate=0.0' "$work/fall.cfg" -o r
check "slew_rate = 0: exit 0, time_slewing 0 (got $rc, $(jf "$work/none/.out" time_slewing))" \
    test "$rc" = 0 -a "$(jf "$work/none/.out" time_slewing)" = 0
t "$work/high" run -q --json --set 'ambs[0].slew_rate=1.0e6' "$work/fall.cfg" -o r
check "slew_rate = 1e6 A/s (never reached): time_slewing 0 (got $rc, $(jf "$work/high/.out" time_slewing))" \
    test "$rc" = 0 -a "$(jf "$work/high/.out" time_slewing)" = 0

finish
