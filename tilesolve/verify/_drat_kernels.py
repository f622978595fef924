"""Loops of the backward DRAT checker (:mod:`tilesolve.verify.drat`), numpy only.

Written once as plain functions over numpy arrays; :mod:`tilesolve.verify.drat` runs them
interpreted on small proofs and compiled by numba (``njit``, rebuilt from the same code) on
large ones. Nothing here is shared with the solvers whose proofs are checked.

The method is drat-trim's (Wetzler, Heule, Hunt, *DRAT-trim: Efficient checking and trimming
using expressive clausal proofs*, SAT 2014, §4): a forward pass adds the lemmas and applies
the deletions with top-level unit propagation until the formula is refuted by propagation;
a backward pass then undoes the steps one by one and checks only the lemmas marked as used
(the *core*), starting from the clauses of the final conflict. Each check propagates core
clauses first and other clauses only when the core stalls, so the marked set stays small.

Data layout
-----------
Literal ``l`` has code ``2|l| + (l < 0)``; ``code ^ 1`` is its negation. Every clause (the
formula's, then one per proof line, deletions included) is ``lits[start[c]:start[c] + size[c]]``
after removing repeated literals, preceded by ``c`` and its size (``lits[start[c] - 2]``,
``lits[start[c] - 1]``: a watch reads one stretch of memory). Clause ``c`` owns two watches,
nodes ``2 start[c]`` and ``2 start[c] + 1``, on its literals in positions 0 and 1. Each literal code has two watch lists, list
``2 code + 1`` for the core clauses and ``2 code`` for the others (a clause moves when it is
marked), so core-first propagation scans only core watches. A list is a vector in a block of
one ``pool`` array (``wl[list]`` = start, length, room; see :func:`w_push`), and an entry is
``node << 32 | blocker``, the blocker a literal of the clause that, when true, lets a check
pass the clause over without reading it. Invariant between checks: a watched literal that is
false has a true partner watch (the trail is closed under unit propagation).

The kernels allocate nothing (the caller hands every array in), so that numba compiles them
without its reference counting (``_nrt=False``), which otherwise costs half the time of the
calls between kernels.
"""

from __future__ import annotations

import numpy as np

MASK = 0x3FFFFFFFFFFFFFFF

#: Kinds of the kernels' parameters, by name ("int" for the others): numba compiles each kernel
#: once, for these types (:func:`tilesolve.verify.drat._kernels`).
PARAMS = {
    **dict.fromkeys(("taut", "active", "val", "core", "done", "seen", "is_del"), "int8s"),
    **dict.fromkeys(("lits", "start", "size", "chash", "mark", "ht_key", "ht_head", "same_prev", "reason", "tpos",
                     "trail", "st", "stack", "tl_before", "target", "counts", "out", "pivot", "pool"), "int64s"),
    "wl": "table",
    **dict.fromkeys(("one", "blk", "core_first"), "flag"),
}

#: The kernels that :mod:`tilesolve.verify.drat` calls (the others are called by kernels only).
ENTRIES = frozenset({"prepare", "forward", "analyze", "backward", "mark_all"})

# status codes of the backward pass (read by tilesolve.verify.drat)
OK, LEMMA_FAILED, NO_EMPTY, EMPTY_NOT_RUP = 0, 1, 2, 3


def lit_hash(code):
    """A 62-bit mix of one literal code (the same interpreted and compiled)."""
    return ((code * 2654435761) ^ (code * 40503 + 97)) & MASK


def prepare(lits, start, size, taut, chash, mark, n_cl):
    """Drop repeated literals, flag tautologies and hash every clause (order-free); ``mark``
    (one entry per literal code, all -1) is left holding clause numbers."""
    for c in range(n_cl):
        b = start[c]
        n = 0
        h = 0
        for k in range(b, b + size[c]):
            x = lits[k]
            if mark[x] == c:
                continue
            if mark[x ^ 1] == c:
                taut[c] = 1
            mark[x] = c
            lits[b + n] = x
            n += 1
            h = (h + lit_hash(x)) & MASK
        size[c] = n
        lits[b - 1] = n
        chash[c] = (h + n) & MASK


def ht_slot(ht_key, ht_head, h):
    """Open-addressing slot of hash ``h`` (its own or the first empty one)."""
    m = ht_key.shape[0] - 1
    i = h & m
    while ht_head[i] >= 0 and ht_key[i] != h:
        i = (i + 1) & m
    return i


def ht_insert(ht_key, ht_head, same_prev, chash, c):
    i = ht_slot(ht_key, ht_head, chash[c])
    same_prev[c] = ht_head[i]
    ht_key[i] = chash[c]
    ht_head[i] = c


def find_clause(ht_key, ht_head, same_prev, chash, lits, start, size, active, mark, d):
    """The most recent active clause with the literals of clause ``d`` (-1 if none)."""
    i = ht_slot(ht_key, ht_head, chash[d])
    if ht_head[i] < 0:
        return -1
    b = start[d]
    for k in range(b, b + size[d]):
        mark[lits[k]] = d
    c = ht_head[i]
    while c >= 0:
        if active[c] == 1 and size[c] == size[d]:
            ok = True
            bc = start[c]
            for k in range(bc, bc + size[c]):
                if mark[lits[k]] != d:
                    ok = False
                    break
            if ok:
                return c
        c = same_prev[c]
    return -1


def w_push(wl, pool, lst, entry):
    """Append ``entry`` to watch list ``lst``. A full list moves to a new block at the pool's
    end with room for as many again (the pool is compacted first when its end is reached)."""
    n = wl[lst, 1]
    if n == wl[lst, 2]:
        last = wl.shape[0] - 1
        if wl[last, 0] + 2 * n + 6 > pool.shape[0]:
            w_compact(wl, pool)
            if wl[last, 0] + 2 * n + 6 > pool.shape[0]:  # the caller's bound on the watches was broken
                raise IndexError("the watch pool is full")
        top = wl[last, 0]
        old = wl[lst, 0]
        pool[top] = lst
        pool[top + 1] = 2 * n + 4
        for i in range(n):
            pool[top + 2 + i] = pool[old + i]
        wl[lst, 0] = top + 2
        wl[lst, 2] = 2 * n + 4
        wl[last, 0] = top + 2 * n + 6
    pool[wl[lst, 0] + n] = entry
    wl[lst, 1] = n + 1


def w_compact(wl, pool):
    """Move the live blocks of the pool down over the abandoned ones, each as full as its list."""
    last = wl.shape[0] - 1
    end = wl[last, 0]
    pos = 0
    top = 0
    while pos < end:
        lst = pool[pos]
        cap = pool[pos + 1]
        if wl[lst, 0] == pos + 2:
            n = wl[lst, 1]
            if n > 0:
                pool[top] = lst
                pool[top + 1] = n
                for k in range(n):
                    pool[top + 2 + k] = pool[pos + 2 + k]
                wl[lst, 0] = top + 2
                top += n + 2
            else:
                wl[lst, 0] = 0
            wl[lst, 2] = n
        pos += cap + 2
    wl[last, 0] = top


def w_remove(wl, pool, lst, node):
    """Remove the entry of watch ``node`` from list ``lst`` (the last entry takes its place)."""
    b = wl[lst, 0]
    n = wl[lst, 1] - 1
    for i in range(b, b + n + 1):
        if pool[i] >> 32 == node:
            pool[i] = pool[b + n]
            wl[lst, 1] = n
            return


def assign(val, reason, tpos, trail, st, code, c):
    val[code] = 1
    val[code ^ 1] = -1
    v = code >> 1
    reason[v] = c
    tpos[v] = st[0]
    trail[st[0]] = code
    st[0] += 1


def backtrack(val, reason, trail, st, p):
    for i in range(p, st[0]):
        code = trail[i]
        val[code] = 0
        val[code ^ 1] = 0
        reason[code >> 1] = -1
    st[0] = p
    st[1] = p
    st[2] = p
    st[3] = -1


def attach(lits, start, size, val, wl, pool, core, c):
    """Watch two literals of clause ``c`` (size >= 2): true first, then unassigned, then false.

    Returns the number of non-false literals among the two watched (0: conflict, 1 with the
    first unassigned: unit).
    """
    b = start[c]
    n = size[c]
    for pos in range(2):
        best = -1
        for k in range(b + pos, b + n):
            x = val[lits[k]]
            if best < 0 or x > val[lits[best]]:
                best = k
                if x == 1:
                    break
        t = lits[b + pos]
        lits[b + pos] = lits[best]
        lits[best] = t
    w_push(wl, pool, 2 * lits[b] + core[c], (2 * b) << 32 | lits[b + 1])
    w_push(wl, pool, 2 * lits[b + 1] + core[c], (2 * b + 1) << 32 | lits[b])
    free = 0
    if val[lits[b]] != -1:
        free += 1
    if val[lits[b + 1]] != -1:
        free += 1
    return free


def detach(lits, start, wl, pool, core, c):
    b = start[c]
    w_remove(wl, pool, 2 * lits[b] + core[c], 2 * b)
    w_remove(wl, pool, 2 * lits[b + 1] + core[c], 2 * b + 1)


def make_core(c, lits, start, size, taut, active, wl, pool, core):
    """Mark clause ``c`` as used; an attached clause moves to the core watch lists."""
    if core[c] == 1:
        return 0
    attached = active[c] == 1 and taut[c] == 0 and size[c] >= 2
    if attached:
        detach(lits, start, wl, pool, core, c)
    core[c] = 1
    if attached:
        b = start[c]
        w_push(wl, pool, 2 * lits[b] + 1, (2 * b) << 32 | lits[b + 1])
        w_push(wl, pool, 2 * lits[b + 1] + 1, (2 * b + 1) << 32 | lits[b])
    return 1


def visit(code, mode, one, blk, lits, start, size, val, reason, tpos, trail, st, wl, pool, core):
    """Clauses watching ``code``'s negation, now false: the core ones (``mode`` 1) or the
    others (0). Returns a falsified clause, or -1.

    A watch entry is ``node << 32 | blocker``: watch ``node`` of the clause whose literals
    start at ``node >> 1`` (its literal in position ``node & 1``) and some literal of that clause; with ``blk`` a clause
    whose blocker is true is passed over unread (only inside a check, which is undone
    whole: at the top level a false watch keeps a true partner watch). With ``one`` the visit
    stops after the first clause it makes unit (drat-trim's core-first order: core clauses
    propagate each new literal first), leaving in ``st[3]`` the position to resume from
    (``-1``: the list's start, ``-2``: the list is done).
    """
    f = code ^ 1
    lst = 2 * f + mode
    i = 0
    if one and st[3] >= 0:
        i = st[3]
    while i < wl[lst, 1]:
        e = pool[wl[lst, 0] + i]
        if blk and val[e & 0xFFFFFFFF] == 1:
            i += 1
            continue
        node = e >> 32
        b = node >> 1
        s = node & 1
        other = lits[b + 1 - s]
        if val[other] == 1:
            pool[wl[lst, 0] + i] = node << 32 | other
            i += 1
            continue
        found = -1
        for k in range(b + 2, b + lits[b - 1]):
            if val[lits[k]] != -1:
                found = k
                break
        if found >= 0:
            x = lits[found]
            lits[found] = f
            lits[b + s] = x
            n = wl[lst, 1] - 1
            pool[wl[lst, 0] + i] = pool[wl[lst, 0] + n]
            wl[lst, 1] = n
            w_push(wl, pool, 2 * x + mode, node << 32 | other)
        elif val[other] == -1:
            return lits[b - 2]
        else:
            assign(val, reason, tpos, trail, st, other, lits[b - 2])
            i += 1
            if one:
                st[3] = i
                return -1
    if one:
        st[3] = -2
    return -1


def propagate(core_first, lits, start, size, val, reason, tpos, trail, st, wl, pool, core):
    """Unit propagation from the queue heads ``st[1]`` (core) and ``st[2]`` (others).

    Without ``core_first`` every clause is visited in one pass (``st[1]`` only).
    """
    while True:
        while st[1] < st[0]:
            code = trail[st[1]]
            st[1] += 1
            c = visit(code, 1, False, core_first, lits, start, size, val, reason, tpos, trail, st, wl, pool, core)
            if c >= 0:
                return c
            if not core_first:
                c = visit(code, 0, False, False, lits, start, size, val, reason, tpos, trail, st, wl, pool, core)
                if c >= 0:
                    return c
        if not core_first or st[2] >= st[0]:
            return -1
        c = visit(trail[st[2]], 0, True, True, lits, start, size, val, reason, tpos, trail, st, wl, pool, core)
        if st[3] == -2:
            st[2] += 1
            st[3] = -1
        if c >= 0:
            return c


def justify(v0, lits, start, size, taut, active, wl, pool, reason, core, done, stack):
    """Mark the reasons of top-level variable ``v0`` and of everything they rest on."""
    top = 0
    stack[top] = v0
    top += 1
    marked = 0
    while top > 0:
        top -= 1
        v = stack[top]
        if done[v] == 1:
            continue
        done[v] = 1
        r = reason[v]
        if r < 0:
            continue
        marked += make_core(r, lits, start, size, taut, active, wl, pool, core)
        b = start[r]
        for k in range(b, b + size[r]):
            u = lits[k] >> 1
            if u != v and done[u] == 0:
                stack[top] = u
                top += 1
    return marked


def analyze(confl, true_var, p, lits, start, size, taut, active, wl, pool, reason, tpos, trail, st, core, done,
            seen, stack):
    """Mark the clauses a conflict (clause ``confl``, or a lemma literal already true on
    variable ``true_var``) rests on: the part of the trail above ``p`` by a backward walk,
    the top level by :func:`justify`.
    """
    if confl >= 0:
        make_core(confl, lits, start, size, taut, active, wl, pool, core)
        b = start[confl]
        for k in range(b, b + size[confl]):
            u = lits[k] >> 1
            if tpos[u] >= p:
                seen[u] = 1
            else:
                justify(u, lits, start, size, taut, active, wl, pool, reason, core, done, stack)
    if true_var >= 0:
        if tpos[true_var] >= p:
            seen[true_var] = 1
        else:
            justify(true_var, lits, start, size, taut, active, wl, pool, reason, core, done, stack)
    for i in range(st[0] - 1, p - 1, -1):
        v = trail[i] >> 1
        if seen[v] == 0:
            continue
        seen[v] = 0
        r = reason[v]
        if r < 0:
            continue
        make_core(r, lits, start, size, taut, active, wl, pool, core)
        b = start[r]
        for k in range(b, b + size[r]):
            u = lits[k] >> 1
            if u == v:
                continue
            if tpos[u] >= p:
                seen[u] = 1
            else:
                justify(u, lits, start, size, taut, active, wl, pool, reason, core, done, stack)


def refutes(c, extra, skip, lits, start, size, taut, active, val, reason, tpos, trail, st, wl, pool, core, done,
            seen, stack):
    """Whether assigning the negation of clause ``c`` (and of clause ``extra`` but its literal
    ``skip``, for a RAT resolvent; ``extra`` -1 for none) and propagating gives a conflict.
    The clauses used are marked; the trail is restored.
    """
    p = st[0]
    true_var = -1
    confl = -1
    for part in range(2):
        cc = c if part == 0 else extra
        if cc < 0 or true_var >= 0:
            continue
        b = start[cc]
        for k in range(b, b + size[cc]):
            x = lits[k]
            if part == 1 and x == skip:
                continue
            if val[x] == 1:
                true_var = x >> 1
                break
            if val[x] == 0:
                assign(val, reason, tpos, trail, st, x ^ 1, -1)
    if true_var < 0:
        confl = propagate(True, lits, start, size, val, reason, tpos, trail, st, wl, pool, core)
    ok = true_var >= 0 or confl >= 0
    if ok:
        analyze(confl, true_var, p, lits, start, size, taut, active, wl, pool, reason, tpos, trail, st, core, done,
                seen, stack)
    backtrack(val, reason, trail, st, p)
    return ok


def truncate(p, lits, start, size, val, reason, trail, st, wl, pool, core, done):
    """Shrink the top-level trail to length ``p`` and re-establish the watch invariant: a
    clause whose false watch was excused by a partner watch that is now unassigned gets a
    non-false literal in its place."""
    old = st[0]
    for i in range(p, old):
        done[trail[i] >> 1] = 0
    backtrack(val, reason, trail, st, p)
    for i in range(2 * p, 2 * old):
        lst = 2 * trail[i >> 1] + (i & 1)
        for j in range(wl[lst, 1]):
            node = pool[wl[lst, 0] + j] >> 32
            b = node >> 1
            s = 1 - (node & 1)
            c = lits[b - 2]
            w = lits[b + s]
            if val[w] == -1:
                for k in range(b + 2, b + lits[b - 1]):
                    x = lits[k]
                    if val[x] != -1:
                        lits[k] = w
                        lits[b + s] = x
                        w_remove(wl, pool, 2 * w + core[c], node ^ 1)
                        w_push(wl, pool, 2 * x + core[c], (node ^ 1) << 32 | lits[b + 1 - s])
                        break


def forward(n_formula, n_steps, is_del, lits, start, size, taut, chash, active, val, reason, tpos, trail, st,
            wl, pool, core, ht_key, ht_head, same_prev, mark, tl_before, target, counts, j0, j1):
    """Forward pass over proof steps ``j0 .. j1 - 1`` (``j0 == -1``: load the formula first).

    ``counts``: [conflict clause, conflict step (-1: the formula), ignored deletions,
    missing deletions, first empty lemma step]. Returns 1 once propagation refutes the
    formula (the pass stops there), else 0.
    """
    if j0 < 0:
        for c in range(n_formula):
            active[c] = 1
            ht_insert(ht_key, ht_head, same_prev, chash, c)
            if size[c] == 0:
                counts[0] = c
                counts[1] = -1
                return 1
        for c in range(n_formula):
            if taut[c] == 0 and size[c] >= 2:
                attach(lits, start, size, val, wl, pool, core, c)
        for c in range(n_formula):
            if taut[c] == 0 and size[c] == 1:
                x = lits[start[c]]
                if val[x] == -1:
                    counts[0] = c
                    counts[1] = -1
                    return 1
                if val[x] == 0:
                    assign(val, reason, tpos, trail, st, x, c)
        confl = propagate(False, lits, start, size, val, reason, tpos, trail, st, wl, pool, core)
        if confl >= 0:
            counts[0] = confl
            counts[1] = -1
            return 1
        j0 = 0
    for j in range(j0, j1):
        c = n_formula + j
        tl_before[j] = st[0]
        if is_del[j] == 1:
            t = find_clause(ht_key, ht_head, same_prev, chash, lits, start, size, active, mark, c)
            target[j] = t
            if t < 0:
                counts[3] += 1
                continue
            ignore = size[t] == 1
            if not ignore and taut[t] == 0:
                for k in range(start[t], start[t] + size[t]):
                    x = lits[k]
                    if val[x] == 1 and reason[x >> 1] == t:
                        ignore = True
                        break
            if ignore:
                target[j] = -2
                counts[2] += 1
                continue
            active[t] = 0
            if taut[t] == 0:
                detach(lits, start, wl, pool, core, t)
            continue
        if size[c] == 0:
            counts[4] = j
            return 0
        active[c] = 1
        ht_insert(ht_key, ht_head, same_prev, chash, c)
        if taut[c] == 1:
            continue
        confl = -1
        if size[c] == 1:
            x = lits[start[c]]
            if val[x] == -1:
                confl = c
            elif val[x] == 0:
                assign(val, reason, tpos, trail, st, x, c)
        else:
            free = attach(lits, start, size, val, wl, pool, core, c)
            if free == 0:
                confl = c
            elif free == 1 and val[lits[start[c]]] == 0:
                assign(val, reason, tpos, trail, st, lits[start[c]], c)
        if confl < 0:
            confl = propagate(False, lits, start, size, val, reason, tpos, trail, st, wl, pool, core)
        if confl >= 0:
            counts[0] = confl
            counts[1] = j
            return 1
    return 0


def backward(n_formula, is_del, pivot, lits, start, size, taut, active, val, reason, tpos, trail, st, wl, pool,
             core, done, seen, stack, tl_before, target, out, j0, j1):
    """Backward pass over proof steps ``j0 - 1`` down to ``j1`` (``j0 > j1``).

    ``out``: [status, failing step, lemmas checked, RAT lemmas]. Returns the step reached.
    """
    for j in range(j0 - 1, j1 - 1, -1):
        c = n_formula + j
        if is_del[j] == 1:
            t = target[j]
            if t >= 0:
                active[t] = 1
                if taut[t] == 0:
                    attach(lits, start, size, val, wl, pool, core, t)
            continue
        active[c] = 0
        if taut[c] == 0 and size[c] >= 2:
            detach(lits, start, wl, pool, core, c)
        if tl_before[j] < st[0]:
            truncate(tl_before[j], lits, start, size, val, reason, trail, st, wl, pool, core, done)
        if core[c] == 0:
            continue
        out[2] += 1
        if refutes(c, -1, 0, lits, start, size, taut, active, val, reason, tpos, trail, st, wl, pool, core, done,
                   seen, stack):
            continue
        # RAT on the lemma's first literal: every resolvent with a clause holding its negation is RUP
        pv = pivot[j]
        ok = pv >= 0
        if ok:
            for d in range(c):
                if active[d] == 0 or taut[d] == 1:
                    continue
                has = False
                for k in range(start[d], start[d] + size[d]):
                    if lits[k] == pv ^ 1:
                        has = True
                        break
                if not has:
                    continue
                make_core(d, lits, start, size, taut, active, wl, pool, core)
                if not refutes(c, d, pv ^ 1, lits, start, size, taut, active, val, reason, tpos, trail, st, wl, pool,
                               core, done, seen, stack):
                    ok = False
                    break
        if not ok:
            out[0] = LEMMA_FAILED
            out[1] = j
            return j
        out[3] += 1
    return j1


def mark_all(n_formula, n_steps, is_del, lits, start, size, taut, active, wl, pool, core):
    """Mark every lemma as used (``lemmas="all"``)."""
    for j in range(n_steps):
        if is_del[j] == 0:
            make_core(n_formula + j, lits, start, size, taut, active, wl, pool, core)
