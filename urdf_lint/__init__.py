"""urdf-lint: expand xacro without ROS, lint robot descriptions at their source lines."""

__version__ = "0.1.0"
