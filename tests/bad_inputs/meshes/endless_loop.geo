// A .geo whose loop runs for minutes: the time limit stops it.
Include "unit_square.geo";
For i In {1:1e9}
  a = i;
EndFor
