#!/usr/bin/env bash
# GSL's BLAS calls must bind to GSL's own CBLAS (libgslcblas), not to a system BLAS that SLICOT
# brings into the process (libblas.so.3, which may be OpenBLAS and exports the CBLAS symbols too):
# the loader binds each symbol to the first library in its breadth-first load order, which is the
# order ldd prints. Each binary given that loads GSL must load libgslcblas before any libblas,
# liblapack or libopenblas (cmake/TouchdownDeps.cmake says how the link keeps it so).
# Usage: cblas_order.sh BINARY...
set -euo pipefail
status=0
for bin in "$@"; do
    order=$(ldd "$bin" | awk '{print $1}')
    gsl=$(grep -n "^libgslcblas" <<<"$order" | head -1 | cut -d: -f1 || true)
    other=$(grep -nE "^lib(blas|lapack|openblas)" <<<"$order" | head -1 | cut -d: -f1 || true)
    if ! grep -q '^libgsl\.' <<<"$order"; then
        echo "ok: $(basename "$bin") does not load GSL"
    elif [ -z "$gsl" ]; then
        echo "FAIL: $(basename "$bin") loads GSL without libgslcblas"; status=1
    elif [ -n "$other" ] && [ "$other" -lt "$gsl" ]; then
        echo "FAIL: $(basename "$bin") loads $(sed -n "${other}p" <<<"$order") before libgslcblas"; status=1
    else
        echo "ok: $(basename "$bin"): libgslcblas first${other:+ (then $(sed -n "${other}p" <<<"$order"))}"
    fi
done
exit $status
