"""The experiment harness: run planners x scenarios x seeds, validate, measure and store."""
