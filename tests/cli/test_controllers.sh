#!/usr/bin/env bash
# Controllers in case files through the tool: `touchdown info` prints each controller (its AMBs,
# coordinates, states, timing and poles) and the AMBs it drives; the poles are checked against
# their closed forms (a notch's poles at its frequency with damping width / (2 frequency), a
# filtered derivative's real pole, a sampled law's z poles mapped to s = ln(z) * sample_rate,
# computed here by Python); cases/rig-notch.cfg is stable (`touchdown modal`) and runs; a bad
# controller exits 2 with one line naming the file, the line or override and the key.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/controllers.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

has() { grep -qF -- "$2" "$1"; }

t "$work/info" info "$src/cases/rig-notch.cfg"
check "info rig-notch: exit 0" test "$rc" = 0
out=$work/info/.out
check "info names the controller, its AMBs, coordinates about the mass centre, states, timing" \
    has "$out" 'controller 0  "rigid-notch": ambs 0, 1 in rigid-body coordinates about z = 1 m, 8 states, continuous'
check "info says which controller drives each AMB" test "$(grep -c '^amb .*controller 0, tau' "$out")" = 2
# the notch: poles at 34.4 Hz with damping width / (2 f) = 6 / 68.8; the derivative filters: 2 kHz, real
zeta=$(python3 -c 'print("%.3g" % (6.0 / (2 * 34.4)))')
check "info's poles: the notch's ($zeta) and the four derivative filters'" \
    has "$out" "poles: 2000 Hz (zeta 1) x4, 34.4 Hz (zeta $zeta) x2"
check "info: the closed loop is stable" has "$out" "stability    stable"

# (its modes are not checked here: the closed-loop analysis takes continuous controllers only)
t "$work/keys" info "$src/tests/data/case/all-keys-controllers.cfg"
out=$work/keys/.out
check "info: a sampled controller's rate, discretisation and delay" \
    has "$out" 'sampled at 8000 Hz (tustin prewarped at 60 Hz), delay 1 sample'
# the zpk block's z poles 0.3 +- 0.4j at 8 kHz: s = 8000 ln(z)
pole=$(python3 -c '
import cmath, math
s = 8000.0 * cmath.log(complex(0.3, 0.4))
print("%.6g Hz (zeta %.3g) x2" % (abs(s) / (2 * math.pi), -s.real / abs(s)))')
check "info: a sampled pole mapped to s = ln(z) rate ($pole)" has "$out" "$pole"
check "info: one delay state per output (4 axes)" has "$out" "z = 0 (delay) x4"
res=$(python3 -c 'import math; print("%.6g" % (100.0 / (2 * math.pi)))')
check "info: the integrator of a PID and a zpk pair in s" has "$out" "0 Hz (integrator) x2, 35.5881 Hz (zeta 0.447) x2"
check "info: the resonant's undamped pair at the speed, 100 rad/s = $res Hz" has "$out" "poles: $res Hz (zeta "

# a law written in z throughout was sampled by nothing: info says so (not the default "tustin"),
# and a discretisation or prewarp written for it, which would do nothing, is refused
t "$work/z" info "$src/tests/data/case/controller-z.cfg"
check "info: a law written in z is not said to be discretised" \
    has "$work/z/.out" 'sampled at 10000 Hz (written in z), delay 1 sample'
t "$work/zd" info --set 'controllers[0].discretisation="zoh"' "$src/tests/data/case/controller-z.cfg"
check "  a discretisation for it: exit 2 naming the key" \
    test "$rc" = 2 -a -n "$(grep -F 'controllers[0].discretisation: discretisation applies to the blocks in s' "$work/zd/.err")"
t "$work/zs" info --set 'controllers[0].law=( { tf = { num = [5.0e3, -4.9e3]; den = [1.0, -0.5]; domain = "z"; }; }, { lowpass = { frequency = 3000.0; }; } )' \
    --set 'controllers[0].discretisation="zoh"' "$src/cases/paper-a-digital.cfg"
check "  and one with a block in s is, by its discretisation" has "$work/zs/.out" 'sampled at 10000 Hz (zoh), delay 1 sample'

# an undamped pair (a resonant block) has zeta 0, not "-0"
t "$work/res" info --set 'controllers[0].translation=( { resonant = { gain = 1.0; frequency = 50.0; }; } )' \
    "$src/cases/rig-notch.cfg"
check "info: a resonant's poles, 50 Hz (zeta 0)" has "$work/res/.out" "poles: 2000 Hz (zeta 1) x2, 50 Hz (zeta 0) x2"
# a damped one: the pair's natural frequency stays 50 Hz, its damping ratio is the block's
t "$work/resd" info --set 'controllers[0].translation=( { resonant = { gain = 1.0; frequency = 50.0; damping = 0.3; }; } )' \
    "$src/cases/rig-notch.cfg"
check "info: a damped resonant's poles, 50 Hz (zeta 0.3)" has "$work/resd/.out" "poles: 2000 Hz (zeta 1) x2, 50 Hz (zeta 0.3) x2"
t "$work/resb" info --set 'controllers[0].translation=( { resonant = { gain = 1.0; damping = 1.0; }; } )' "$src/cases/rig-notch.cfg"
check "  a damping of 1: exit 2 naming the key" \
    test "$rc" = 2 -a -n "$(grep -F 'controllers[0].translation[0].resonant.damping: must be >= 0 and < 1 (got 1)' "$work/resb/.err")"
t "$work/ress" info --set speed=1e-6 --set 'controllers[0].translation=( { resonant = { gain = 1.0; }; } )' \
    "$src/cases/rig-notch.cfg"
check "  a resonant at a speed below the frequency bound: exit 2 naming the speed, not a frequency never written" \
    test "$rc" = 2 -a -n "$(grep -F "resonant.frequency: absent, it is the case's speed / (2 pi) = 1.59155e-07 Hz (speed 1e-06 rad/s)" "$work/ress/.err")"

t "$work/modal" modal --csv '' --hdf5 '' "$src/cases/rig-notch.cfg"
check "modal rig-notch: exit 0 and stable" grep -q '^modes at 90 rad/s (stable)' "$work/modal/.out"

t "$work/run" run --set end_time=0.02 -o "$work/run/rn" "$src/cases/rig-notch.cfg"
check "run rig-notch to 0.02 s: exit 0" test "$rc" = 0

t "$work/bad" info --set 'controllers[0].delay=1' "$src/cases/rig-notch.cfg"
check "a delay without sample_rate: exit 2" test "$rc" = 2
check "  one line on stderr naming the override and the key" \
    test "$(wc -l <"$work/bad/.err")" = 1 -a -n "$(grep -F -e "--set 'controllers[0].delay=1': controllers[0].delay: delay applies to a sampled controller" "$work/bad/.err")"
t "$work/bad2" run -o "$work/bad2/x" --set 'controllers[0].ambs=[0, 1, 5]' "$src/cases/rig-notch.cfg"
check "an AMB that does not exist: run exits 2, one line, no file" \
    test "$rc" = 2 -a "$(wc -l <"$work/bad2/.err")" = 1 -a -z "$(ls "$work/bad2")"
check "  naming the entry of ambs" grep -qF 'controllers[0].ambs[2]: AMB 5 does not exist' "$work/bad2/.err"

finish
