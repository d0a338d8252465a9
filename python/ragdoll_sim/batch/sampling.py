"""Counter-based random draws: run i's parameters are a pure function of (seed, i, parameter).

Each draw hashes (seed, index, stream, counter) with splitmix64, so it needs no state: the same
index gives the same values in any order, in any process, on any machine. Only integer
arithmetic and IEEE additions, multiplications, divisions and square roots are used (Python's
math.log and math.cos may round differently across C libraries): the normal draw uses the
polar method with a logarithm of our own.
"""
import math

_MASK = (1 << 64) - 1
_LN2 = 0.6931471805599453
_SQRT_HALF = 0.7071067811865476


def splitmix64(x):
    """splitmix64's output for state x (an int, taken mod 2**64): a well-mixed 64-bit int."""
    z = (x + 0x9E3779B97F4A7C15) & _MASK
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & _MASK
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & _MASK
    return z ^ (z >> 31)


def stream_id(name):
    """A 64-bit stream number for a parameter name (FNV-1a of its UTF-8 bytes)."""
    h = 0xCBF29CE484222325
    for b in name.encode("utf-8"):
        h = ((h ^ b) * 0x100000001B3) & _MASK
    return h


def uniform01(seed, index, stream, counter):
    """A double in [0, 1) with 53 random bits, from (seed, index, stream, counter)."""
    h = splitmix64(seed & _MASK)
    for part in (index, stream, counter):
        h = splitmix64(h ^ (part & _MASK))
    return (h >> 11) * (1.0 / 9007199254740992.0)


def det_log(x):
    """Natural logarithm of a finite x > 0 with basic IEEE operations only (same bits anywhere).

    x = m 2^e with m in [sqrt(1/2), sqrt(2)); log m = 2 atanh(z), z = (m - 1) / (m + 1),
    |z| < 0.172, whose series to z^31 is below 1e-17 relative.
    """
    m, e = math.frexp(x)
    if m < _SQRT_HALF:
        m *= 2.0
        e -= 1
    z = (m - 1.0) / (m + 1.0)
    z2 = z * z
    s = 0.0
    for k in range(31, 1, -2):
        s = (s + 1.0 / k) * z2
    return 2.0 * z * (1.0 + s) + e * _LN2


class Draws:
    """The draws of one run (seed, index): uniform, normal and choice values by parameter name."""

    def __init__(self, seed, index):
        self.seed = seed
        self.index = index

    def _u(self, name, counter):
        return uniform01(self.seed, self.index, stream_id(name), counter)

    def uniform(self, name, lo, hi):
        """lo + (hi - lo) u."""
        return lo + (hi - lo) * self._u(name, 0)

    def normal(self, name, mean, std):
        """mean + std n, n standard normal (Marsaglia's polar method)."""
        for k in range(0, 256, 2):
            u = 2.0 * self._u(name, k) - 1.0
            v = 2.0 * self._u(name, k + 1) - 1.0
            s = u * u + v * v
            if 0.0 < s < 1.0:
                return mean + std * (u * math.sqrt(-2.0 * det_log(s) / s))
        return mean  # 128 rejections in a row: probability below 1e-85

    def choice(self, name, options):
        """One of `options`, each with probability 1 / len(options)."""
        i = int(self._u(name, 0) * len(options))
        return options[min(i, len(options) - 1)]


def draw(spec, draws, name):
    """The value of a validated distribution spec (scenario.py) for parameter `name`."""
    kind = spec["kind"]
    if kind == "constant":
        return spec["value"]
    if kind == "uniform":
        return draws.uniform(name, spec["lo"], spec["hi"])
    if kind == "normal":
        return draws.normal(name, spec["mean"], spec["std"])
    if kind == "choice":
        return draws.choice(name, spec["options"])
    raise ValueError("unknown distribution kind %r" % kind)
