"""The one exception for input that formopt cannot take.

InputError (a ValueError) names the bad input and why: a scene key, a data file, a posture the
impact map cannot take, an option. The command line turns it into one line and exit status 2;
any other exception is a bug in formopt and keeps its traceback.
"""


class InputError(ValueError):
    """Input formopt cannot take; the message names it and says why (one line)."""


def one_line(text, limit: int = 120) -> str:
    """`text` on one line (control characters escaped), cut to `limit` characters."""
    text = "".join(c if c.isprintable() else repr(c)[1:-1] for c in str(text))
    return text if len(text) <= limit else text[:limit - 5] + "[...]"
