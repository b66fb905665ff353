"""Helpers shared by the tests of every part: real and generated test images (`images`),
hand-made corner maps (`regions`), and the pytest fixtures and seeds (`fixtures`, loaded
as a plugin by the repository's conftest.py)."""
