#!/bin/sh
# Writes the torsion recordings of this folder with `strainwave synth` (run from the repository root after a build:
# sh cases/recordings/make_recordings.sh). Each is a torque-twist loop of a catalog size, cycled 4 times to +-rated
# torque (CSG rating at ratio 100), whose stiffness follows the published law of that size
# (../shared/reference/catalog_torsional_stiffness.md), with hysteresis and lost motion inside the catalog's limits
# (< 1 arcmin each; the catalog's lost motion holds the elastic twist 2 * 0.04 T_R / K1 and the play) and encoder noise as a 22-bit output encoder gives it: white 0.5 arcsec + AR(1) 1 arcsec (phi 0.9),
# quantised to 2 pi / 2^22 rad. To keep the fitter from being proved on its own laws only, sizes 14 and 20 have
# Bouc-Wen friction (n = 2 and n = 1) instead of the fitter's exponential branch transition (rounded stiffness
# corners, which three straight segments cannot follow at this noise, are tested in tests/reconcile/test_multi.cpp). The baseline C_tau is the flexspline body: size 17 from `strainwave fem
# cases/cup_size17.toml` (phi0 5.86e-4 rad at 31 N*m), sizes 14 and 20 scaled from it by (pitch diameter)^-3.
# Sampling: 1000 samples per cycle, so the torque moves 2 pi A / 1000 per sample at zero (0.063 N*m at size 14), a
# third of the play's transition: play (a jump at zero torque) and friction (a jump after each reversal) are told
# apart by where the loop jumps, which needs several samples inside the play's transition.
set -e
bin=${1:-build/strainwave}
dir=cases/recordings
noise="--white 2.42e-6 --ar1 4.85e-6 --ar1-phi 0.9 --quantum 1.4980e-6 --samples 4000 --cycles 4 --period 0.05"

$bin --quiet synth --kind torsion --compliance 3.38e-5 --torque 10 $noise --seed 14 --out $dir/size14_torsion.csv \
  --effects "stiffness_nonlinearity:K1_Nm_per_rad=4700,K2_Nm_per_rad=6100,K3_Nm_per_rad=7100,T1_Nm=2.0,T2_Nm=6.9,friction_bouc_wen:loss_rad=0.000203622,transition_Nm=0.5,n=2,lost_motion:width_rad=8.72665e-05,transition_Nm=0.15" \
  --meta "size=14" --meta "rated_torque_Nm=10" --meta "baseline_compliance_rad_per_Nm=3.38e-5" \
  --meta "drive=cup-type strain wave gear, size 14, ratio 100 (CSF/CSG class): catalog three-segment stiffness (K1 4700, K2 6100, K3 7100 N*m/rad; T1 2.0, T2 6.9 N*m); Bouc-Wen friction (n 2) with 0.7 arcmin hysteresis loss at +-10 N*m; play 0.3 arcmin (catalog lost motion 0.89 arcmin)" \
  --meta "test=wave generator locked, torque cycled 4 times to +-10 N*m on the output; twist from a 22-bit output encoder"

$bin --quiet synth --kind torsion --compliance 1.89e-5 --torque 31 $noise --seed 17 --out $dir/size17_torsion.csv \
  --effects "stiffness_nonlinearity:K1_Nm_per_rad=10000,K2_Nm_per_rad=14000,K3_Nm_per_rad=16000,T1_Nm=3.9,T2_Nm=12,hysteresis:loss_rad=0.000174533,transition_Nm=1.5,lost_motion:width_rad=3.49066e-05,transition_Nm=0.4" \
  --meta "size=17" --meta "rated_torque_Nm=31" --meta "baseline_compliance_rad_per_Nm=1.89e-5" \
  --meta "drive=cup-type strain wave gear, size 17, ratio 100 (CSF/CSG class): catalog three-segment stiffness (K1 1.0e4, K2 1.4e4, K3 1.6e4 N*m/rad; T1 3.9, T2 12 N*m); Dahl-type friction (exponential branch transition over 1.5 N*m) with 0.6 arcmin hysteresis loss at +-31 N*m; play 0.12 arcmin (catalog lost motion 0.97 arcmin)" \
  --meta "test=wave generator locked, torque cycled 4 times to +-31 N*m on the output; twist from a 22-bit output encoder"

$bin --quiet synth --kind torsion --compliance 1.16e-5 --torque 52 $noise --seed 20 --out $dir/size20_torsion.csv \
  --effects "stiffness_nonlinearity:K1_Nm_per_rad=16000,K2_Nm_per_rad=25000,K3_Nm_per_rad=29000,T1_Nm=7,T2_Nm=25,friction_bouc_wen:loss_rad=0.000145444,transition_Nm=2.5,n=1,lost_motion:width_rad=2.90888e-05,transition_Nm=0.8" \
  --meta "size=20" --meta "rated_torque_Nm=52" --meta "baseline_compliance_rad_per_Nm=1.16e-5" \
  --meta "drive=cup-type strain wave gear, size 20, ratio 100 (CSF/CSG class): catalog three-segment stiffness (K1 1.6e4, K2 2.5e4, K3 2.9e4 N*m/rad; T1 7, T2 25 N*m); Bouc-Wen friction (n 1) with 0.5 arcmin hysteresis loss at +-52 N*m; play 0.1 arcmin (catalog lost motion 0.99 arcmin)" \
  --meta "test=wave generator locked, torque cycled 4 times to +-52 N*m on the output; twist from a 22-bit output encoder"
