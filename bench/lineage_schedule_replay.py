#!/usr/bin/python3
"""Replays a two-worker fill of the 46 one-direction keys under both batch
orders, from the per-key seconds a real fill logged.

The wall clock of one fill mixes the order with the machine's spread (the same
root at N = 65536 took 105 s in one run and 128 s in another, both times beside
the same key). A replay holds the seconds fixed and changes only the order, so
it isolates what the order costs:

  children first  a free worker takes the first waiting key whose parent is
                  done, else reads ahead (the server before this change);
  roots first     a free worker reads ahead for the next root, every warm key
                  waiting, else takes the first waiting key whose parent is
                  done (server/service_precompute.cc).

Both read the keys in the server's lineage order (by root, then by depth).
The one-direction lineage: roots every 7 degrees from 1 (the cold keys in the
log), every other key continuing from its neighbour one degree nearer its root.
The replay of the log's own order is checked against the log's wall clock.

  bench/lineage_schedule_replay.py LOG [LOG ...]
"""
import datetime
import re
import sys

PATTERN = re.compile(r'(\S+) info optimize (start|done) n=\d+ dirs=1:(\d+)\b(.*)')


def read(path):
    start, seconds, cold, first, last = {}, {}, set(), None, None
    for line in open(path).read().splitlines():
        m = PATTERN.match(line)
        if not m:
            continue
        t = datetime.datetime.fromisoformat(m.group(1))
        key = int(m.group(3))
        if m.group(2) == 'start':
            start[key] = t
            first = first or t
            if 'warm' not in m.group(4):
                cold.add(key)
        else:
            seconds[key] = (t - start[key]).total_seconds()
            last = t
    return seconds, sorted(cold), (last - first).total_seconds()


def lineage(keys, roots):
    root_of = {k: min(roots, key=lambda r: (abs(r - k), r)) for k in keys}
    parent = {k: None if k == root_of[k] else (k - 1 if k > root_of[k] else k + 1) for k in keys}
    order = sorted(keys, key=lambda k: (root_of[k], abs(k - root_of[k])))
    return parent, order


def replay(seconds, parent, order, roots_first, workers=2):
    now, done, running, waiting, j = 0.0, set(), {}, [], 0
    unresolved = set()

    def ready_waiting():
        for k in waiting:
            if parent[k] not in unresolved:
                waiting.remove(k)
                return k
        return None

    def next_key():
        nonlocal j
        if not roots_first:
            k = ready_waiting()
            if k is not None:
                return k
        while j < len(order):
            k = order[j]
            j += 1
            if parent[k] is not None and (roots_first or parent[k] in unresolved):
                unresolved.add(k)
                waiting.append(k)
                continue
            unresolved.add(k)
            return k
        return ready_waiting()

    while len(done) < len(order):
        while len(running) < workers:
            k = next_key()
            if k is None:
                break
            running[k] = now + seconds[k]
        k = min(running, key=running.get)
        now = running.pop(k)
        done.add(k)
        unresolved.discard(k)
    return now


def main():
    for path in sys.argv[1:]:
        seconds, roots, wall = read(path)
        if len(seconds) != 46:
            sys.exit('%s: %d keys optimized, expected the 46 one-direction keys' % (path, len(seconds)))
        parent, order = lineage(sorted(seconds), roots)
        old = replay(seconds, parent, order, roots_first=False)
        new = replay(seconds, parent, order, roots_first=True)
        busy = sum(seconds.values())
        print('%s: logged %.1f s; replayed: children first %.1f s (%.2f s a set), roots first %.1f s '
              '(%.2f s a set); no idle core %.1f s' % (path, wall, old, old / 46, new, new / 46, busy / 2))


if __name__ == '__main__':
    main()
