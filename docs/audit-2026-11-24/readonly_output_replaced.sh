#!/bin/bash
# as a non-root user: a read-only (0444) existing -o target is silently replaced, exit 0
d=$(mktemp -d); cp /work/main/samples/four_bar.toml $d/; echo old > $d/ro.csv; chmod 444 $d/ro.csv; chown -R nobody $d
runuser -u nobody -- /tmp/audit/kinema eval $d/four_bar.toml -o $d/ro.csv; echo "rc=$?"; ls -l $d/ro.csv; head -1 $d/ro.csv
rm -rf $d
