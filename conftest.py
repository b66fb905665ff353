"""pytest set-up for the whole repository: the shared fixtures and seeds."""

pytest_plugins = ["fastnms.testing.fixtures"]
