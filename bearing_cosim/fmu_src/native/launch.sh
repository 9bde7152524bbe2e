#!/bin/sh
# Starts the model process of the bearing FMU (resources/model_process.py) with the first Python that fits:
#   1. the runtime bundled in resources/python/ (standalone FMUs);
#   2. $BEARING_FMU_PYTHON (it must fit: no fall-through when set);
#   3. the Python the FMU was built with (thin FMUs: resources/build_python.txt);
#   4. python3 on PATH.
# An installed Python fits when it can import numpy, scipy and numba (checked without importing them). Exits 3
# with the reason on stderr (the native layer passes it to the master's logger) when none fits.
res=$(dirname "$0")
need="numpy scipy numba"
check='import importlib.util as u, sys
m = [n for n in sys.argv[1:] if u.find_spec(n) is None]
print(" ".join(m)); sys.exit(1 if m else 0)'

if [ -f "$res/python/bin/python3" ]; then
    # the bundled runtime, isolated from the master's Python settings; run through the dynamic loader when the
    # unpack lost the executable bit (zip extractors that ignore modes)
    for v in $(env | sed -n 's/^\(PYTHON[A-Za-z0-9_]*\)=.*/\1/p'); do unset "$v"; done
    PYTHONHOME="$res/python"
    PYTHONNOUSERSITE=1
    export PYTHONHOME PYTHONNOUSERSITE
    if [ -x "$res/python/bin/python3" ]; then
        exec "$res/python/bin/python3" -s "$@"
    fi
    for ld in /lib64/ld-linux-x86-64.so.2 /lib/x86_64-linux-gnu/ld-linux-x86-64.so.2; do
        [ -f "$ld" ] && exec "$ld" "$res/python/bin/python3" -s "$@"
    done
    echo "bearing FMU: cannot execute the bundled Python $res/python/bin/python3 (not executable, no dynamic loader" \
         "found)" >&2
    exit 3
fi
if [ -n "$BEARING_FMU_PYTHON" ]; then
    if ! missing=$("$BEARING_FMU_PYTHON" -E -s -c "$check" $need 2>&1); then
        echo "bearing FMU: BEARING_FMU_PYTHON=$BEARING_FMU_PYTHON cannot run the model: missing $missing" >&2
        exit 3
    fi
    exec "$BEARING_FMU_PYTHON" -E -s "$@"
fi
tried=""
build=""
[ -f "$res/build_python.txt" ] && build=$(cat "$res/build_python.txt")
for py in "$build" python3; do
    [ -n "$py" ] || continue
    if command -v "$py" >/dev/null 2>&1; then
        if missing=$("$py" -E -s -c "$check" $need 2>&1); then
            exec "$py" -E -s "$@"
        fi
        tried="$tried $py (missing $missing);"
    else
        tried="$tried $py (not found);"
    fi
done
echo "bearing FMU: no Python to run the model: this FMU carries no runtime (build it with --standalone) and no" \
     "installed Python fits:$tried set BEARING_FMU_PYTHON to a Python with $need" >&2
exit 3
