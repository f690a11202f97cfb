"""Point the ROS 2 wheels' exported CMake targets at this environment's Python and numpy headers.

The ROS 2 Jazzy wheels on PyPI were built in a manylinux container; their exported CMake targets
(``share/<pkg>/cmake/*Export.cmake``) name that container's include directories,
``/opt/python/cp311-cp311/include/python3.11`` and ``.../site-packages/numpy/_core/include``.
CMake refuses an imported target whose include directory does not exist, so building any interface
package against the wheels fails until these paths name the headers of the environment at hand.

Run with the environment's own interpreter; it edits only files inside ``sys.prefix``, is idempotent
and prints how many files it changed.
"""
import pathlib
import sys
import sysconfig

import numpy

WHEEL_BUILDER_PYTHON_INCLUDE = "/opt/python/cp311-cp311/include/python3.11"
WHEEL_BUILDER_NUMPY_INCLUDE = "/opt/python/cp311-cp311/lib/python3.11/site-packages/numpy/_core/include"


def main() -> int:
    replacements = {
        WHEEL_BUILDER_NUMPY_INCLUDE: numpy.get_include(),
        WHEEL_BUILDER_PYTHON_INCLUDE: sysconfig.get_paths()["include"],
    }
    changed = 0
    for cmake_file in pathlib.Path(sys.prefix, "share").glob("*/cmake/*.cmake"):
        text = cmake_file.read_text()
        if "/opt/python/" not in text:
            continue
        new_text = text
        for old, new in replacements.items():
            new_text = new_text.replace(old, new)
        if new_text != text:
            cmake_file.write_text(new_text)
            changed += 1
    print(f"fix_wheel_cmake_paths: {changed} CMake export file(s) now name this environment's headers")
    return 0


if __name__ == "__main__":
    sys.exit(main())
