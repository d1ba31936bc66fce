"""Chooses the Python tests that the sanitizer half of make check runs, and writes the others to
python/tests/sanitize-except.txt (they run in the plain half only).

The rule: under the sanitizers, every entry that the suite's tests (those not marked slow) record
with tests/tools/pytest_libcalls.py is reached by at least one chosen test: each library
function called, with each outcome seen (success, failure status or NULL), each constant read,
each command of the whirl program run. The files whose subject is memory or threads
(ALWAYS below) are always chosen. The rest are chosen greedily, the test with the most entries
not yet reached per processor second first, until every entry is reached.

    make                                       # build/libwhirl.so and build/whirl
    cd python && PYTHONPATH=../tests/tools WHIRL_LIBCALLS=/tmp/calls.json WHIRL_BUILD=../build \\
        /usr/bin/python3 -m pytest -q -p no:cacheprovider -p pytest_libcalls -m "not slow" tests
    cd .. && /usr/bin/python3 tests/tools/python_sanitize_list.py /tmp/calls.json \\
        > python/tests/sanitize-except.txt

The summary (entries, tests and processor seconds chosen and left out) goes to standard error.
"""
import json
import sys

# The files whose tests are about memory and threads: the reason the sanitizers run at all.
ALWAYS = ("test_memory.py::", "test_threads.py::")


def choose(calls, seconds):
    """The chosen node ids (a set) for {nodeid: entries} and {nodeid: seconds}."""
    tests = {k: set(v) for k, v in calls.items() if k != "import"}
    chosen = {t for t in tests if t.startswith(ALWAYS)}
    reached = set(calls.get("import", ()))
    for t in chosen:
        reached |= tests[t]
    wanted = set().union(*tests.values()) - reached
    while wanted:
        # the most new entries per processor second (a floor of 10 ms for the cheapest); ties
        # to the node id, so that the choice is the same on every run of the same record
        best = max((t for t in tests if t not in chosen and tests[t] & wanted),
                   key=lambda t: (len(tests[t] & wanted) / max(seconds.get(t, 0.0), 0.01),
                                  [-ord(c) for c in t]))
        chosen.add(best)
        wanted -= tests[best]
    return chosen


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: python_sanitize_list.py CALLS.json > python/tests/sanitize-except.txt")
    with open(sys.argv[1]) as f:
        record = json.load(f)
    calls, seconds = record["calls"], record["seconds"]
    chosen = choose(calls, seconds)
    left = sorted(t for t in calls if t != "import" and t not in chosen)
    entries = set().union(*(set(v) for v in calls.values()))
    cost = sum(seconds.get(t, 0.0) for t in calls if t != "import")
    kept = sum(seconds.get(t, 0.0) for t in chosen)
    print("# The Python tests that the sanitizer half of make check leaves out (they run in the\n"
          "# plain half): chosen by tests/tools/python_sanitize_list.py, whose comment gives the\n"
          "# rule and the commands that write this file. Under the sanitizers the %d tests that\n"
          "# run reach all %d entries (library functions with each outcome, constants, commands\n"
          "# of the program) that the %d tests record; recorded processor time %.1f s of %.1f s.\n"
          "# A test not listed here (a new one) runs in both halves."
          % (len(chosen), len(entries), len(calls) - 1, kept, cost))
    for t in left:
        print(t)
    print("%d entries; %d tests chosen (%.1f s), %d left out (%.1f s)"
          % (len(entries), len(chosen), kept, len(left), cost - kept), file=sys.stderr)


if __name__ == "__main__":
    main()
