!> Search interval: no contact can be missed between searches.
program test_contact_interval
  use core_kinds, only: rk
  use contact_search, only: search_interval
  use check, only: check_true, check_summary
  implicit none
  real(rk) :: dt, speed, margin, moved
  integer :: k, j, trial, seed_size
  integer, allocatable :: seed(:)
  real(rk) :: r(4)

  ! Margin used up by the capture tolerance: search every cycle.
  call check_true('no room: k = 1', search_interval(1.0_rk, 1.0_rk, 1.0_rk, 0.1_rk, 1.1_rk, 50) == 1)
  ! Nothing moves: the cap.
  call check_true('at rest: k = cap', search_interval(1.0_rk, 0.1_rk, 0.0_rk, 0.1_rk, 1.1_rk, 50) == 50)
  ! Constant dt: room 0.9, closing 2 x 1 x 0.1 = 0.2 per cycle -> 4 cycles.
  call check_true('constant dt: k = 4', search_interval(1.0_rk, 0.1_rk, 1.0_rk, 0.1_rk, 1.0_rk, 50) == 4)
  ! Random cases: the motion over k steps fits the room, over k+1 it does not
  ! (unless capped or k = 1).
  call random_seed(size=seed_size)
  allocate(seed(seed_size))
  seed = 4242
  call random_seed(put=seed)
  do trial = 1, 2000
    call random_number(r)
    margin = 0.01_rk + r(1)
    speed = 10.0_rk * r(2)
    dt = 1.0e-3_rk + 0.05_rk * r(3)
    k = search_interval(margin, 0.1_rk * margin, speed, dt, 1.0_rk + 0.2_rk * r(4), 100)
    moved = 0.0_rk
    do j = 1, k
      moved = moved + 2.0_rk * speed * dt * (1.0_rk + 0.2_rk * r(4))**j
    end do
    if (k > 1 .and. moved > 0.9_rk * margin) then
      call check_true('random: motion over k steps within the room', .false.)
      exit
    end if
    if (k < 100) moved = moved + 2.0_rk * speed * dt * (1.0_rk + 0.2_rk * r(4))**(k + 1)
    if (k < 100 .and. k > 1 .and. moved <= 0.9_rk * margin) then
      call check_true('random: k is the largest such number', .false.)
      exit
    end if
  end do
  call check_true('random: 2000 cases consistent', trial > 2000)
  call check_summary()
end program test_contact_interval
