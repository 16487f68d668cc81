"""sva host tools: mission generator, independent SPEC checker, exact reference,
IH, OR-tools peer, paper benchmark and plots (docs/tools.md)."""
__version__ = "0.4.0"
