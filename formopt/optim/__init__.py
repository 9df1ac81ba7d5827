"""The posture NLP: decision variables, constraints, IPOPT multi-start, post-solve report."""

# The public modules (imported on use).
__all__ = ["constraints", "multistart", "objective", "posture", "solution", "variables"]
