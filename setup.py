# The Python module `apex` (python/apex: scripting a runtime through its services), beside the
# generated apex.msg and apex.srv; catkin_python_setup() in CMakeLists.txt uses it. Not for pip.
from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=['apex'], package_dir={'': 'python'}))
