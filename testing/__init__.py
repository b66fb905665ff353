"""Helpers shared by the tests of every part: real and generated test images (`images`),
hand-made corner maps (`regions`), OpenCV's ORB as a reference (`opencv_orb`), and the
pytest fixtures and seeds (`fixtures`, loaded as a plugin by the repository's
conftest.py)."""
