"""The posture NLP: decision variables, constraints, IPOPT multi-start, post-solve report."""
