"""The installed Python package (run by tests/consumer/run.cmake with PYTHONPATH set to the
install prefix's dist-packages): imported from there, the same question as consumer.cpp."""
import sys
from fractions import Fraction

import surfcert

assert surfcert.__file__.startswith(sys.argv[1]), surfcert.__file__
d = surfcert.distance("x^2 + y^2 + z^2 = 1", {"type": "sphere", "center": [3, 0, 0], "radius": 0.5})
assert d.status == "certified" and d.result.distance.lower == Fraction(3, 2), d
print(d.to_json())
