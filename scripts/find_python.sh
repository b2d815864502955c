#!/bin/sh
# find_python.sh [MODULE...] - prints the path of the Python that the tests, the Makefile's recipes and tools/*.sh
# run their Python with, or says on stderr what is missing and exits 1. MODULEs: what it must import (default: h5py
# numpy; the tests that draw a plot add matplotlib).
#
# The rule, the same everywhere (tests/test_util.c's test_python calls this script):
#  - $PYTHON when set and not empty: an explicit choice, used if it imports the modules, else refused with what it
#    lacks (never silently replaced by another);
#  - else the first of the `python3` on PATH and /usr/bin/python3 that imports every MODULE. Debian's python3-h5py
#    and friends serve /usr/bin/python3, but a machine with h5py from pip or conda has it only in the python3 on its
#    PATH (a GPU machine was seen so: /usr/bin/python3 without h5py); the one on PATH goes first so that a venv or
#    conda environment the user activated wins when it has them. On the development VM the `python3` on PATH is a
#    pyenv one without numpy, so /usr/bin/python3 is the one found.
# What it prints is the path of the interpreter it tried (as `command -v` gives it), not its sys.executable: a python3
# that is a wrapper script setting the environment (PYTHONPATH, a module system) must run as it was probed.
# POSIX sh: the C tests run it through popen (/bin/sh), which may be dash.
mods=${*:-h5py numpy}

# "h5py, numpy and matplotlib"
words() {
    list=
    i=0
    for w in "$@"; do
        i=$((i + 1))
        if [ -z "$list" ]; then list=$w
        elif [ "$i" -eq $# ]; then list="$list and $w"
        else list="$list, $w"
        fi
    done
    printf '%s' "$list"
}

# imports each module named in its arguments; prints "ok", or "lacks M, N" and exits 1
probe='import sys
missing = []
for m in sys.argv[1:]:
    try:
        __import__(m)
    except ImportError as e:
        missing.append(m if getattr(e, "name", None) == m else "%s (%s)" % (m, e))
    except Exception as e:
        missing.append("%s (%s: %s)" % (m, type(e).__name__, e))
if missing:
    print("lacks " + ", ".join(missing))
    sys.exit(1)
print("ok")'

nl='
'
# try INTERPRETER: 0 and its path in $found, or 1 and why not in $why
try() {
    path=$(command -v "$1" 2> /dev/null)
    if [ -z "$path" ]; then
        why="is not found"
        return 1
    fi
    # shellcheck disable=SC2086 # one module a word
    out=$("$path" -c "$probe" $mods 2> /dev/null)
    rc=$?
    last=${out##*"$nl"} # its last line (no tail: the probe runs with any PATH)
    if [ "$rc" -eq 0 ] && [ "$last" = ok ]; then
        found=$path
        return 0
    fi
    case $last in
    lacks\ *) why=$last ;;
    *) why="does not run (exit status $rc)" ;;
    esac
    return 1
}

# shellcheck disable=SC2086
need=$(words $mods)
pkgs=
for m in $mods; do pkgs="$pkgs python3-$m"; done

if [ -n "${PYTHON:-}" ]; then
    if try "$PYTHON"; then
        echo "$found"
        exit 0
    fi
    echo "find_python: PYTHON=$PYTHON $why; a Python with $need is needed: name one that has them, or unset" \
        "PYTHON to take the first of python3 on PATH and /usr/bin/python3 that has them" >&2
    exit 1
fi

msg=
on_path=$(command -v python3 2> /dev/null)
if [ -n "$on_path" ]; then
    if try "$on_path"; then
        echo "$found"
        exit 0
    fi
    msg="python3 on PATH ($on_path) $why"
else
    msg="no python3 on PATH"
fi
if try /usr/bin/python3; then
    echo "$found"
    exit 0
fi
echo "find_python: no Python with $need: $msg; /usr/bin/python3 $why. Install them (Debian: apt-get install$pkgs)" \
    "or name a Python that has them: PYTHON=/path/to/python3" >&2
exit 1
