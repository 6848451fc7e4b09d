//! Fibril mechanics of chapter 5: tilted-fibril and seta-branch stiffness, the Lennard-Jones fibril-substrate energy and the single-spring model, Eqs. (5.11)-(5.20).
