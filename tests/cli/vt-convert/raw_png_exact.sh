# raw -> png is exact for every sample type png stores (u8, u16) and channel count: every texel of
# every tile decodes to the same value; empty and shared tiles stay so. raw -> raw keeps f16.
set -euo pipefail
while read -r opts; do
  "$VT_SYNTH" r.vts $opts
  "$VT_CONVERT" r.vts -o p.vts --codec png
  "$VT_STORE_CHECK" structure r.vts p.vts
  "$VT_STORE_CHECK" same-tiles r.vts 0 p.vts 0
  "$VT_INFO" --verify p.vts
done <<'CASES'
--channels 4
--channels 3 --empty --flat
--channels 2 --sample u16 --empty
--channels 1 --sample u16 --flat --seed 5 --size 257x131 --tile 32 --border 3
CASES
"$VT_SYNTH" h.vts --sample f16 --channels 3 --empty
"$VT_CONVERT" h.vts -o h2.vts --codec raw -j 2
"$VT_STORE_CHECK" same-bytes h.vts 0 h2.vts 0
