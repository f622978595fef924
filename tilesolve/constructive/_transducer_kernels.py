"""Inner loop of the transducer route (see :mod:`tilesolve.constructive.transducer`).

Callers take the function from ``KERNELS.pick(work)``: plain Python on small transducers,
numba-compiled on large ones, the same output on both (see :mod:`._jit`). Compiled, a
transducer of the route's size limit (20 M transitions) is split into strongly connected
components in about a second, so that one step of the search stays short between two looks
at the deadline.
"""

from __future__ import annotations

import numpy as np

from tilesolve.constructive._jit import Kernels, kernel


@kernel()
def scc_labels(indptr, targets, n):
    """The strongly connected component of each of ``n`` states (Tarjan 1972, iterative).

    Parameters
    ----------
    indptr, targets : numpy.ndarray
        int64 adjacency in compressed rows: the successors of state ``v`` are
        ``targets[indptr[v]:indptr[v + 1]]``.
    n : int

    Returns
    -------
    numpy.ndarray
        ``(n,)`` int64 component numbers, ``0 ..``; two states share one exactly when each
        reaches the other.
    """
    index = np.full(n, -1, np.int64)
    low = np.zeros(n, np.int64)
    on_stack = np.zeros(n, np.bool_)
    stack = np.empty(n, np.int64)  # Tarjan's stack of visited states
    frames = np.empty(n, np.int64)  # the depth-first path (the recursion, made explicit)
    next_edge = np.empty(n, np.int64)  # the next successor of each state of the path
    label = np.full(n, -1, np.int64)
    counter = 0
    n_comp = 0
    sp = 0
    for root in range(n):
        if index[root] != -1:
            continue
        depth = -1
        w = root  # the state to visit next (-1: none)
        while True:
            if w >= 0:  # visit w: number it, push it, descend into it
                index[w] = counter
                low[w] = counter
                counter += 1
                stack[sp] = w
                sp += 1
                on_stack[w] = True
                depth += 1
                frames[depth] = w
                next_edge[depth] = indptr[w]
                w = -1
            if depth < 0:
                break
            v = frames[depth]
            e = next_edge[depth]
            if e < indptr[v + 1]:
                next_edge[depth] = e + 1
                x = targets[e]
                if index[x] == -1:
                    w = x
                elif on_stack[x] and index[x] < low[v]:
                    low[v] = index[x]
                continue
            if low[v] == index[v]:  # v is the root of a component: pop it
                while True:
                    sp -= 1
                    x = stack[sp]
                    on_stack[x] = False
                    label[x] = n_comp
                    if x == v:
                        break
                n_comp += 1
            depth -= 1
            if depth >= 0:
                u = frames[depth]
                if low[v] < low[u]:
                    low[u] = low[v]
    return label


#: States plus transitions from which compiling pays: interpreted, the loop costs about 7 us a
#: state or transition (0.9 s for 50,000 states and 90,000 transitions); importing numba and
#: loading the compiled kernel from its cache, 1-3 s on the loaded 2-core machine.
THRESHOLD = 100_000

KERNELS = Kernels(globals(), THRESHOLD)
