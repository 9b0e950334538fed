//! Rendering a plan for people: text, Graphviz dot, JSON.
