"""Adapters that put real engines under the conformance battery (issue 19)."""
