// Includes a device that never ends.
Include "/dev/zero";
