"""urdf-lint: expand xacro without ROS, lint robot descriptions at their source lines."""
from . import lazy

__version__ = "0.1.0"

# ``dataclasses`` imports ``inspect`` (~7 ms) only to write docstrings for classes without one;
# every dataclass here has its own, so ``inspect`` loads only when something really uses it
lazy.defer("inspect")
