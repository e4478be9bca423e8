"""Case writers: OpenFOAM dictionaries, fields and meshes (foam), coupled cases (coupled)."""
