"""The 3D page: `urdf-lint preview` (a local server) and the review page of `diff --html`."""
