"""What the scene generators share: one glTF buffer filled view by view. Standard library only."""


class GltfBuffer:
    """The bytes of buffer 0 and the bufferViews into it."""

    def __init__(self):
        self.data = bytearray()
        self.views = []

    def add_view(self, data, target):
        """Appends data as a new bufferView, 4-byte aligned as accessors need (target 34962 for
        vertex attributes, 34963 for indices); returns the view's index."""
        while len(self.data) % 4:
            self.data.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(data), "target": target})
        self.data.extend(data)
        return len(self.views) - 1
