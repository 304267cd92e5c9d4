"""The failures a TFDEM command reports by their message alone (tfdem.frontdoor: exit 2): each
module's error class derives from Reported, so the front door needs to know none of them."""


class Reported(Exception):
    """A failure whose message names what is wrong and the fix; no traceback is shown."""
