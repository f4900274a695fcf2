#pragma once
// A test hook that proves the GIL is released during extraction without timing anything:
// armed with n parties, every extraction waits inside the GIL-free section until n extractions
// are there at once. Threads that held the GIL could never all arrive, so the wait would end
// by its timeout (a guard against hanging, not a measurement) and raise aief.Error.
namespace aief::python {

// parties 0 disarms. Bound as aief._aief._arm_extraction_rendezvous.
void arm_extraction_rendezvous(int parties, double timeout_s);
// Called by every extraction with the GIL released; returns at once when disarmed.
void extraction_rendezvous();

}  // namespace aief::python
