"""Checks of the documentation and of the version: the README as a front page, the links of
the README and docs/, and the one version source, the file VERSION."""
