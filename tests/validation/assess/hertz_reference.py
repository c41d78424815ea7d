#!/usr/bin/env python3
"""touchdown's Hertz point contact (td_hertz_point, td_ball_inner_contact_stress) against an
independent solution with scipy's complete elliptic integrals, the closed form of the circle, and
Hamrock & Brewe's approximations (J. Lubr. Technol. 105, 1983), which are within a few per cent for
curvature ratios up to 100. Args: the hertz_probe binary. Exit 1 on any difference."""
import math
import subprocess
import sys

from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

E_STAR = 207.5e9 / (2.0 * (1.0 - 0.3 ** 2))  # steel on steel, E = 207.5 GPa, nu = 0.3
failures = []


def exact(load, rx, ry, estar):
    """Johnson (1985) sec. 4.2: solve B/A for e^2 (scipy's parameter m = e^2) with brentq."""
    A, B = 0.5 / max(rx, ry), 0.5 / min(rx, ry)
    if B / A - 1.0 < 1e-12:
        a = (3.0 * load / (8.0 * estar * A)) ** (1.0 / 3.0)
        return a, a, 3.0 * load / (2.0 * math.pi * a * a)
    # 1 - m from 1e-14 to 1: the ratio (E/(1-m) - K)/(K - E) - B/A changes sign
    f = lambda lq: (ellipe(1 - 10 ** lq) / 10 ** lq - ellipk(1 - 10 ** lq)) / (ellipk(1 - 10 ** lq) - ellipe(1 - 10 ** lq)) - B / A
    lq = brentq(f, -14.0, -1e-9, xtol=1e-15, rtol=1e-15, maxiter=500)
    m = 1.0 - 10 ** lq
    kme = (ellipk(m) - ellipe(m)) / m
    a = (3.0 * load * kme / (2.0 * math.pi * estar * A)) ** (1.0 / 3.0)
    b = a * math.sqrt(1.0 - m)
    return a, b, 3.0 * load / (2.0 * math.pi * a * b)


def hamrock_brewe(load, rx, ry, estar):
    """The approximations: k = alpha^(2/pi), E = 1 + (pi/2 - 1)/alpha, alpha = R_y / R_x (R_y >= R_x)."""
    Rx, Ry = min(rx, ry), max(rx, ry)
    alpha = Ry / Rx
    k = alpha ** (2.0 / math.pi)
    Ebar = 1.0 + (math.pi / 2.0 - 1.0) / alpha
    R = 1.0 / (1.0 / Rx + 1.0 / Ry)
    Ep = 2.0 * estar
    Dy = 2.0 * (6.0 * k * k * Ebar * load * R / (math.pi * Ep)) ** (1.0 / 3.0)
    Dx = 2.0 * (6.0 * Ebar * load * R / (math.pi * k * Ep)) ** (1.0 / 3.0)
    return Dy / 2.0, Dx / 2.0, 6.0 * load / (math.pi * Dx * Dy)


def close(what, got, want, rel):
    err = abs(got - want) / abs(want)
    if not err <= rel:
        failures.append("%s: %.12g against %.12g (relative %.3g > %.3g)" % (what, got, want, err, rel))
    return err


def main():
    probe = subprocess.Popen([sys.argv[1]], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def ask(line):
        probe.stdin.write(line + "\n")
        probe.stdin.flush()
        return probe.stdout.readline().split()

    # ball on inner raceway of the 55 mm bearing, balls of 6 mm and 20 mm, flat to conforming grooves,
    # a circle (sphere on sphere), a cylinder-like contact
    geometries = [(4.755e-3, 0.1443), (3.0e-3, 0.08), (1.0e-2, 1.0e-2), (2.0e-3, 2.0), (5.0e-3, 7.0e-3)]
    worst_exact = worst_hb = 0.0
    for rx, ry in geometries:
        for load in (1.0, 350.0, 2.5e4):
            a, b, p = (float(v) for v in ask("point %r %r %r %r" % (load, rx, ry, E_STAR)))
            ea, eb, ep = exact(load, rx, ry, E_STAR)
            for name, g, w in (("a", a, ea), ("b", b, eb), ("p_max", p, ep)):
                worst_exact = max(worst_exact, close("rx=%g ry=%g P=%g %s" % (rx, ry, load, name), g, w, 1e-9))
            if max(rx, ry) / min(rx, ry) <= 100.0:  # the range the approximations were fitted over
                ha, hb, hp = hamrock_brewe(load, rx, ry, E_STAR)
                worst_hb = max(worst_hb, close("Hamrock-Brewe p_max rx=%g ry=%g" % (rx, ry), p, hp, 0.03))
    # the circle in closed form (a sphere of radius 2R on a sphere of radius 2R: relative radius R),
    # a = (3 P R / (4 E*))^(1/3), p_max = 3 P / (2 pi a^2)
    a, b, p = (float(v) for v in ask("point 100.0 0.01 0.01 %r" % E_STAR))
    ac = (3.0 * 100.0 * 0.01 / (4.0 * E_STAR)) ** (1.0 / 3.0)
    close("circle a", a, ac, 1e-14)
    close("circle p_max", p, 3.0 * 100.0 / (2.0 * math.pi * ac * ac), 1e-14)
    # the ball bearing: Stribeck's 5 F_r / Z on the most loaded ball, the raceway's radii
    D, dm, fi, Z, F = 0.0111, 0.0775, 0.52, 10, 3000.0
    got = float(ask("ball %r %d %r %r %r" % (F, Z, D, dm, fi))[0])
    rx = 1.0 / (2.0 / D + 2.0 / (dm - D))
    ry = 1.0 / (2.0 / D - 1.0 / (fi * D))
    close("ball on inner raceway", got, exact(5.0 * F / Z, rx, ry, E_STAR)[2], 1e-9)
    for bad in ("point -1 0.01 0.01 1e11", "point 1 0 0.01 1e11", "point 1 0.01 0.01 0"):
        if ask(bad) != ["invalid"]:
            failures.append("%s: not refused" % bad)
    if ask("ball 100 10 0.0111 0.0775 0.5")[0] != "nan":
        failures.append("a groove conformity of 0.5 gave a stress")
    probe.stdin.close()
    probe.wait()
    for f in failures:
        print("FAIL: " + f)
    print("Hertz: %d geometries x 3 loads, exact to %.2g relative, Hamrock-Brewe within %.2g" %
          (len(geometries), worst_exact, worst_hb))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
