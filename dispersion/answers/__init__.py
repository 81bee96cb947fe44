"""The answers of commands: results in a practitioner's units that render themselves."""
