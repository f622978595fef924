"""Packings published in the class notes (Lagae 2007, §5.5), transcribed as data.

Fig. 5.11 is a recursive corner packing and Fig. 5.12 a recursive Wang packing over 4 colours,
found by the notes' parallel backtracking search (280 CPU-days and about 23 CPU-years). Both
are printed with row 0 at the top, which is tilesolve's convention; the test suite checks them
with the independent verifier. :func:`known_packing` returns one, optionally under a random
symmetry of the problem (translation, rotation, reflection, colour permutation), which maps
packings to packings.
"""

from __future__ import annotations

import numpy as np

from tilesolve.constructive.packing import random_symmetry
from tilesolve.errors import MethodNotApplicable

__all__ = ["FIG_5_11_CORNER_4", "FIG_5_12_WANG_4", "KNOWN", "known_packing"]

_FIG_5_11 = """
     56 108  57  28 180  62 156 182  46 248 239  27 228  59 252  47
    206 179 222 119 237 251  95 245 143 242 159 118 157 246 223 183
     43 232 123 221 151 214 103 249  15 240  79 241 111 217  87 229
    186 174 250 127 125 109 185 254  31 244  63 236 187 110 121 173
    198 163 218 231 219 167 234 203 115 253 255 191 238 139 226 155
     45 184 126 189  78 177 158  54 220 247 207 243 175  58 172 122
    131 210 199 195  35 200  99 233  75 209  55 204 147 230 171 202
     36 104  41  40 168  10 160 170  26 116 205  51  92 181 190  30
    165 138 162 154 166  42 152 134  82 213  39 216  71 225 235  91
    149  22 164  90 133 146  86  37  88 117 141 114  61 140 178  94
     89 101 153 102  25 100  73 161 106 201   3 208 215   7 224 107
     66 145  70 129  98 137  34 136 130  50  44 120  93  53 188 142
      4  80  21  20 132  18 148  38  24 212 135 194  83 197 211  23
     17  84  85  69  33  72  97 169  74 113  29  52  76  49 124  77
     64  65  81   5 128   2 144 150   6 192  67 193  19 196 227  11
      0  16  68   1  32   8  96 105   9  48  60  12 112  13 176  14
"""

_FIG_5_12 = """
     61 123  47  46 174 190 171  62  63 191 223 253 255 251 239 222
    204 156 233 238 234 250 187 235 254 203 220 205 236 158 237 206
    213 249 139 244 159 189 175 142 248 155 217 221 245 207 252 219
     94 157 173 126 247 231 202 216 185 143 140 232 110 218 201 172
    224 198 228 214 125 127 151 181 167 230 246 183 215 141 188 199
     30  77  92  93 197 208 117  79 124 119  95 109  78 240 243 111
    194 212 209 241  91  57 107 226 210 121 227 242 211  53  31 229
     26  89  37  38 138 152 153  41  42 186  59  15  60  75 196 108
    166 150 105 106 154 137 136 164 170 182 179 195 192 184  87 225
     70  88 149 165 134 132 168  86 169 118  27  45  58 163 122  43
    100 146 101  74  72 104 162  90 133 120 147 193 176  11 180 135
     66  36  98 130 144 161  10 160 102 178  39  54  55 131 116 103
     20  85  21   5  40  22 145  25  73  56  99 114 115   7 112  71
     81  69  68  84 129  96   6 128 148 177  35  50  51  67  52  83
     17  65  64  80  33  18  97  34  82  29  49   3  48  19 113  23
      0   4  16   1   8  24   9  32   2 200  12  28  13  44  14  76
"""


def _parse(text: str) -> np.ndarray:
    return np.array([[int(v) for v in line.split()] for line in text.strip().splitlines()], dtype=np.int64)


#: Fig. 5.11: a recursive tile packing of the complete corner tile set over 4 colours.
FIG_5_11_CORNER_4 = _parse(_FIG_5_11)
#: Fig. 5.12: a recursive tile packing of the complete Wang tile set over 4 colours.
FIG_5_12_WANG_4 = _parse(_FIG_5_12)

#: (kind, colours) -> (figure, packing).
KNOWN: dict[tuple[str, int], tuple[str, np.ndarray]] = {
    ("corner", 4): ("Fig. 5.11", FIG_5_11_CORNER_4),
    ("wang", 4): ("Fig. 5.12", FIG_5_12_WANG_4),
}


def known_packing(kind: str, colors: int, seed=None) -> tuple[str, np.ndarray]:
    """``(figure, grid)``: the notes' packing, under a random symmetry when ``seed`` is given.

    Examples
    --------
    >>> fig, g = known_packing("corner", 4)
    >>> fig, g.shape, int(g[-1, 0])
    ('Fig. 5.11', (16, 16), 0)
    """
    if (kind, colors) not in KNOWN:
        have = ", ".join(f"{k} C={c}" for k, c in KNOWN)
        raise MethodNotApplicable(f"the notes publish packings only for {have}; use method 'sat' or 'cpsat'")
    fig, g = KNOWN[(kind, colors)]
    g = g.copy()
    if seed is not None:
        g = random_symmetry(g, kind, colors, seed)
    return fig, g
